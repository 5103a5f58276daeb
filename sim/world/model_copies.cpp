#include "sim/world/model_copies.h"

#include <algorithm>
#include <cmath>

namespace occsim {

double animationTime(const SceneModel& model, double duration_s, double phase_s, double t) {
    const double u = model.time_offset_s + phase_s + model.speed * t;
    if (!(duration_s > 0.0)) return 0.0;  // a single key: its value, whatever the time
    switch (model.mode) {
        case AnimationMode::Clamp:
            return std::clamp(u, 0.0, duration_s);
        case AnimationMode::PingPong: {
            double w = std::fmod(u, 2.0 * duration_s);
            if (w < 0.0) w += 2.0 * duration_s;
            return w > duration_s ? 2.0 * duration_s - w : w;
        }
        case AnimationMode::Loop:
            break;
    }
    double w = std::fmod(u, duration_s);
    if (w < 0.0) w += duration_s;
    // The end of a loop shows the last key, not the first: a loop whose last key equals its
    // first looks the same either way, and one that does not should not jump early.
    if (w == 0.0 && u > 0.0) return duration_s;
    return w;
}

ModelPoseBuffers makePoseBuffers(const std::vector<SceneModel>& models) {
    ModelPoseBuffers buffers;
    for (const SceneModel& m : models) {
        buffers.per_model.emplace_back(*m.model);
        buffers.animation_times.emplace_back(m.model->animations.size(), 0.0);
    }
    return buffers;
}

void poseCopies(const Scene& scene, double t, const std::vector<ModelCopy>& copies,
                ModelPoseBuffers& buffers, std::vector<ObjectPose>& poses,
                std::vector<Aabb>* boxes) {
    for (const ModelCopy& copy : copies) {
        const SceneModel& m = scene.models[copy.model];
        std::vector<double>& times = buffers.animation_times[copy.model];
        for (size_t a = 0; a < times.size(); ++a) {
            times[a] = animationTime(m, m.model->animations[a].duration_s, copy.phase_s, t);
        }
        ModelPoseScratch& scratch = buffers.per_model[copy.model];
        poseModel(*m.model, times, m.playing, scratch);
        const glm::dmat3 anchor =
            glm::dmat3(glm::mat3_cast(copy.anchor.rotation)) * glm::dmat3(copy.anchor.linear);
        for (uint32_t j = 0; j < m.objectsPerCopy(); ++j) {
            if (!copy.rigid && !(copy.animated && m.object_animated[j])) continue;
            const glm::dmat4& world = scratch.visit_world[m.model->object_visit[j]];
            const uint32_t o = copy.first_object + j;
            ObjectPose& pose = poses[o];
            pose.position = copy.anchor.position + anchor * glm::dvec3(world[3]);
            pose.rotation = glm::quat(1.0f, 0.0f, 0.0f, 0.0f);
            pose.linear = glm::mat3(anchor * glm::dmat3(world));
            if (boxes) {
                (*boxes)[o] =
                    worldBox(scene.mesh_bounds[scene.object_mesh[o]], pose, scene.culling_origin);
            }
        }
    }
}

std::vector<uint32_t> movedObjects(const Scene& scene, const std::vector<Mover>& movers,
                                   const std::vector<ModelCopy>& copies) {
    std::vector<uint8_t> listed(scene.objectCount(), 0);
    std::vector<uint32_t> moved;
    auto add = [&](uint32_t o) {
        if (!listed[o]) moved.push_back(o);
        listed[o] = 1;
    };
    for (const Mover& mover : movers) {
        if (mover.copy < 0) add(mover.object);
    }
    for (const ModelCopy& copy : copies) {
        const SceneModel& m = scene.models[copy.model];
        for (uint32_t j = 0; j < m.objectsPerCopy(); ++j) {
            if (copy.rigid || (copy.animated && m.object_animated[j])) add(copy.first_object + j);
        }
    }
    return moved;
}

}  // namespace occsim
