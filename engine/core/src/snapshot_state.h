// Internal pieces shared by world_snapshot.cpp and snapshot_format.cpp.
#pragma once

#include <string>

#include "rigidlab/force.h"
#include "rigidlab/world_snapshot.h"

namespace rigidlab {

// Stands for a force a snapshot file records only by kind and id (Force::clone returned nullptr
// when it was written): World::restore swaps in the restoring world's force of that id and kind.
class PlaceholderForce final : public Force {
 public:
  explicit PlaceholderForce(std::string kind) : kind_(std::move(kind)) {}
  ~PlaceholderForce() override;
  void evaluate(const ForceInput& in, ForceOutput& out) override;
  std::string_view kind() const override { return kind_; }
  const std::string& kindName() const { return kind_; }

 private:
  std::string kind_;
};

}  // namespace rigidlab
