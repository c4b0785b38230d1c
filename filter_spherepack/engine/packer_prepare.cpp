// Sec. 4.3 and 4.1: the splat radii and the box grid the growth runs on (packer_steps.h).
#include "packer_steps.h"

namespace growth {
namespace spherepack {
namespace detail {

// Sec. 4.3: the splat radii, from the points' own neighbourhoods (independent of d).
std::vector<float> splatRadii(const InputCloud& in, const Sizes& z, const Params& params, const Renumbering& order,
                              Stat& st, Progress& progress) {
  SplatSizeStats splatStats;
  std::vector<float> radius =
      computeSplatRadii(in.points, in.normals, z.s, kSplatFirstReachPerAreaSpacing * z.scale.areaSpacing,
                        params.localSplatSizes, &splatStats, &progress, params.threads,
                        order.orig.empty() ? nullptr : &order.orig);
  st.meanSplatRadius = splatStats.meanRadius;
  st.splatsUnbounded = splatStats.unbounded;
  st.splatsClamped = splatStats.clamped;
  return radius;
}

// Sec. 4.1: the box grid, normal filter and box normals. A splat larger than d is referred to by
// every box it comes within d of (sec. 4.4 needs all splats within d of a vertex), not only by
// those its centre is within d of. The normals of the boxes holding input points are deferred:
// computed on another thread while the growth (one thread) runs, which asks for them as it goes
// (BoxGrid::startNormals).
void buildBoxGrid(BoxGrid& grid, const InputCloud& in, const std::vector<float>& radius, double d,
                  const Params& params, const Renumbering& order, Stat& st, Progress& progress) {
  std::vector<float> extraReach;
  {
    size_t large = 0;
    for (float r : radius) large += r > kLargeSplatPerD * d ? 1 : 0;
    if (large > 0) {
      extraReach.assign(radius.size(), 0.0f);
      for (size_t i = 0; i < radius.size(); ++i)
        if (radius[i] > kLargeSplatPerD * d) extraReach[i] = radius[i];
    }
  }
  grid.build(in.points, in.normals, d, &progress, params.threads, /*deferNormals=*/true,
             order.rank.empty() ? nullptr : &order.rank, extraReach.empty() ? nullptr : &extraReach);
  std::vector<float>().swap(extraReach);
  st.boxes = grid.boxCount();
}

} // namespace detail
} // namespace spherepack
} // namespace growth
