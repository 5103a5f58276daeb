// Posing the moving copies of glTF models (sim/world/world.h: SceneModel, ModelCopy): each
// animation's own time from the simulation time, the model posed through its hierarchy, and each
// object's pose and box from its copy's anchor and its node's world matrix. No allocation once
// the buffers are sized.
#pragma once

#include "sim/world/world.h"

namespace occsim {

// The time of an animation of `duration_s` at simulation time t: time_offset + phase + speed · t,
// wrapped by the model's mode (loop: modulo the duration; clamp: held at the ends; ping_pong:
// forward then backward).
double animationTime(const SceneModel& model, double duration_s, double phase_s, double t);

ModelPoseBuffers makePoseBuffers(const std::vector<SceneModel>& models);

// Poses every object of `copies` that moves (all objects of a rigid copy, the animated ones of
// an animated copy) at simulation time t; refreshes their boxes when `boxes` is given.
void poseCopies(const Scene& scene, double t, const std::vector<ModelCopy>& copies,
                ModelPoseBuffers& buffers, std::vector<ObjectPose>& poses,
                std::vector<Aabb>* boxes);

// The objects a step moves, each once, in a fixed order (movers' objects, then copies').
std::vector<uint32_t> movedObjects(const Scene& scene, const std::vector<Mover>& movers,
                                   const std::vector<ModelCopy>& copies);

}  // namespace occsim
