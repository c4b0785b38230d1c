#pragma once
// The hole pass's state (Mesher::HolePass; g2s_repair.cpp), shared with the handle pass
// (g2s_handles.cpp), which closes the loops of its cuts with it.
#include "g2s_mesher.h"

#include <array>
#include <cmath>
#include <cstdint>
#include <unordered_map>
#include <vector>

namespace growth {
namespace g2s {

// The hole pass's state over the loops of one closeHoles call: the live faces at each point, the
// long faces by cells, the faces added so far, and the loop being closed with the faces near it.
class Mesher::HolePass {
public:
  explicit HolePass(Mesher& m);
  // Closes loop `original` whole, if need be with one of its faces taken out (counted in st).
  void closeLoop(const std::vector<std::uint32_t>& original, HoleStat& st);
  // The live faces that the loop's least-area triangulation (with the ears' tests but the
  // crossing test) meets, into out (sorted); false when there is none (or no such triangulation).
  bool blockers(const std::vector<std::uint32_t>& original, std::vector<std::uint32_t>& out);
  // Face f (live, appended to the mesh: by commit, or by another pass) is known to the later
  // closures' tests.
  void noteAdded(std::uint32_t f) {
    for (std::uint32_t v : m_.tri_[f]) {
      added_[v].push_back(f);
      hasAdded_[v] = 1;
    }
    addIfLong(f);
  }

private:
  struct NearFace {
    double lo[3], hi[3];
    std::uint32_t g;
  };
  struct Ear {
    double score;
    std::uint32_t index; // the point's rank_
  };
  static constexpr long kMaxCells = 64;

  // The cells of the box [boxLo, boxHi] (their number, at most kMaxCells + 1 along each axis).
  long boxCells(const double boxLo[3], const double boxHi[3], long lo[3], long hi[3]) const;
  // The cells of triangle t's box.
  long cellRange(const Triangle& t, long lo[3], long hi[3]) const;
  static std::uint64_t cellKey(long x, long y, long z) {
    return (std::uint64_t(x & 0x1FFFFF) << 42) | (std::uint64_t(y & 0x1FFFFF) << 21) | std::uint64_t(z & 0x1FFFFF);
  }
  // Face f into the long-face cells when an edge of it is longer than `longest_`.
  void addIfLong(std::uint32_t f) {
    const Triangle& t = m_.tri_[f];
    const double limit = longest_ * longest_;
    const P3 &a = pts_[t[0]], &b = pts_[t[1]], &c = pts_[t[2]];
    if ((a - b).SquaredNorm() > limit || (b - c).SquaredNorm() > limit || (c - a).SquaredNorm() > limit) addLong(f);
  }
  void addLong(std::uint32_t f);
  // The live face on half-edge v→w (-1: none), and its third point.
  std::int64_t faceOn(std::uint32_t v, std::uint32_t w) const;
  std::uint32_t thirdPoint(std::uint32_t f, std::uint32_t v, std::uint32_t w) const {
    const Triangle& t = m_.tri_[f];
    return t[0] != v && t[0] != w ? t[0] : t[1] != v && t[1] != w ? t[1] : t[2];
  }
  P3 normal(std::uint32_t a, std::uint32_t b, std::uint32_t c) const {
    return (pts_[b] - pts_[a]) ^ (pts_[c] - pts_[a]);
  }
  static double cosBetween(const P3& x, const P3& y) {
    const double d = std::sqrt(x.SquaredNorm() * y.SquaredNorm());
    return d > 0 ? (x * y) / d : -1.0;
  }
  // The faces that a triangle on `points` can meet, into near_ (the points into gathered_).
  void gatherNear(const std::vector<std::uint32_t>& points);
  // Every one of `points` was gathered for.
  bool gatheredHolds(const std::vector<std::uint32_t>& points) const;
  // Triangle t (on gathered points) meets no live face, no face added before and none of pending_
  // (exactly).
  bool meetsNothing(const Triangle& t) const;
  // Triangle t meets none of pending_ (exactly).
  bool meetsNoPending(const Triangle& t) const;
  // Triangle t (on gathered points) meets a live face (anyMeeting): the faces it meets are found
  // once per loop (met_), live or not.
  bool meetsMesh(const Triangle& t) const;
  // The live faces near the gathered points (near_ and the long ones) that t meets, or (all) those
  // of near_ live or not: stop(face) for each, until it returns true (then true).
  template <bool all, class F> bool anyMeeting(const Triangle& t, F&& stop) const;
  // loop_'s triangulation of least area among those whose triangles pass the ears' tests, and the
  // crossing test if crossingTest: its triangles as loop positions (i, j, k), outermost first.
  bool leastArea(bool crossingTest, std::vector<std::array<size_t, 3>>& out);
  // Closes loop_ by ears; true with the new triangles in pending_ and the point–edge map.
  bool close();
  // Where the ears fail: loop_ closed by its triangulation of least area among those whose every
  // triangle passes the ears' tests (no existing edge, room, fold, crossing nothing); the
  // triangles are then checked against each other and for folds across the new edges. Same
  // result convention as close().
  bool closeLeastArea();
  // The loop's triangles into the mesh.
  void commit(HoleStat& st);

  Mesher& m_;
  const P3* pts_;
  const std::vector<P3>& pos_;
  std::vector<std::uint32_t> first_, at_; // live faces at each point (faceIndex)
  // Faces with an edge longer than longest_ (few) are found by their boxes, the others at the
  // points within a new triangle's enclosing radius plus longest_.
  const double longest_;
  // The long faces in a hash of cells 4·longest wide (each in the cells its box meets; the few
  // meeting more than kMaxCells cells in a list of their own).
  const double cell_;
  const P3 origin_;
  std::unordered_map<std::uint64_t, std::vector<std::uint32_t>> longCells_;
  std::vector<std::uint32_t> hugeFaces_;
  std::unordered_map<std::uint32_t, std::vector<std::uint32_t>> added_; // faces added here, by point
  std::vector<char> hasAdded_;
  const double minCos_;
  std::vector<Triangle> pending_;
  std::vector<std::uint32_t> seen_;
  std::vector<NearFace> near_;
  struct TriangleHash {
    size_t operator()(const Triangle& t) const {
      return size_t((std::uint64_t(t[0]) * 0x9E3779B97F4A7C15ull) ^ (std::uint64_t(t[1]) * 0xC2B2AE3D27D4EB4Full) ^
                    (std::uint64_t(t[2]) * 0x165667B19E3779F9ull));
    }
  };
  struct Met {
    std::uint32_t face; // a face met (~0u: none known)
    bool none;          // no face met, live or not
  };
  mutable std::unordered_map<Triangle, Met, TriangleHash> met_; // meetsMesh's answers for this loop
  std::vector<std::uint32_t> gathered_, tryPoints_;
  // The long faces whose box meets the loop's box are in near_ too (from the cells that box
  // covers), unless it covers more than kMaxCells cells: then each triangle looks them up.
  bool nearHasLong_ = false;
  std::vector<char> inNear_;
  // The loop being closed, opp_[i]: the third point of the face on loop half-edge
  // loop_[i]→loop_[i+1]; face_[i]: that face in the loop as found.
  std::vector<std::uint32_t> loop_, opp_, face_;
  std::vector<Ear> ears_;
  std::vector<std::uint32_t> rank_; // close(): each loop point's place in the loop at the start
  std::vector<std::array<size_t, 3>> split_;
  std::vector<signed char> valid_; // leastArea's state and area per triangle, best value and split per part
  std::vector<double> area_, best_;
  std::vector<P3> edgeNormal_;
  std::vector<std::array<size_t, 2>> failedParts_;
  std::vector<std::uint32_t> bestSplit_;
};


} // namespace g2s
} // namespace growth
