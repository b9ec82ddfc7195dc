#pragma once
/// Which objects of a scene move: the names a user gives (`voxhap simulate --move NAME`),
/// each an object or a group (scene.h), and every other object, which stays static.
///
/// A group moves as ONE object of its name: the objects under it merge (their parts keep
/// their own colours but collide as one rigid body, mass from all their closed meshes, at
/// the default density). A group may only merge plain objects: one that holds an object
/// named by a node's `extras.voxhap` is refused, since those settings (a density, the
/// object's own name) make it an object of its own; move that object, or put the extras
/// on the group's node. Load time only; allocates; throws voxhap::Error naming the scene
/// and the name.

#include <memory>
#include <span>
#include <string>
#include <vector>

#include "haptics/scene/scene.h"

namespace voxhap {

/// The objects a list of names picks, and the rest. Points into the scene it was made
/// from, which must outlive it, and into its own `merged`.
struct ObjectSelection {
  /// One per name, in the order given: an object of the scene, or a group's merged object.
  std::vector<const SceneObject*> picked;
  /// Every object of the scene that no picked name holds, in scene order.
  std::vector<const SceneObject*> rest;
  /// The objects merged from groups, owned here (each stays where it is when moved).
  std::vector<std::unique_ptr<SceneObject>> merged;
};

/// Picks `names` out of `scene`. Throws voxhap::Error for a name that is neither an
/// object nor a group (the message lists what can be moved), a name given twice, two names
/// that hold the same object (a group and a part of it, or nested groups), and a group that
/// holds an object named by extras (groupMoveProblem).
ObjectSelection selectObjects(const Scene& scene, std::span<const std::string> names);

/// Why `group` of `scene` cannot move as one object, or "" when it can.
std::string groupMoveProblem(const Scene& scene, const SceneGroup& group);

/// What can be moved, for messages: "objects: a, b; groups: g (a, c)".
std::string movableNames(const Scene& scene);

/// The objects that move when the user names none: the scene's dynamic ones, in order.
std::vector<std::string> dynamicObjectNames(const Scene& scene);

}  // namespace voxhap
