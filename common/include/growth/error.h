#pragma once
// Errors the engine reports to its host. The MeshLab glue catches them and turns them into the
// filter's error text (MeshLab does not catch exceptions itself).
#include <stdexcept>
#include <string>

namespace growth {

// Bad input or parameters: the message is written for the user and says what to do.
class Error : public std::runtime_error {
public:
  explicit Error(const std::string& what) : std::runtime_error(what) {}
};

// The progress callback asked to stop. Nothing of the partial result may be kept.
class Cancelled : public std::runtime_error {
public:
  Cancelled() : std::runtime_error("cancelled by the user") {}
};

} // namespace growth
