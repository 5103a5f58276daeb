// DepthRasterDevice's GPU-driven draws (occsim/culling/contract/gpu_driven_draws.h): the two
// phases over the CPU raster, each slot's visibility kept here, as the GL device keeps it in a
// buffer. What the GL device does with compute shaders and indirect draws, done in plain loops.
#include <algorithm>
#include <cassert>

#include "occsim/culling/testing/depth_raster_device.h"

namespace occsim {

void DepthRasterDevice::resetVisibility() {
    std::fill(slot_passed_.begin(), slot_passed_.end(), 0);
}

void DepthRasterDevice::drawFirstPhase(const GpuUnits& units) {
    assert(units.slots.size() == units.bounds.size() && units.forced.size() == units.bounds.size());
    assert(units.object_units.size() == units.objects.size());
    units_ = units;
    ++gpu_frame_;
    if (slot_passed_.size() < units.slot_count) slot_passed_.resize(units.slot_count, 0);
    for (const uint32_t slot : units.forgotten_slots) {
        assert(slot < units.slot_count);
        slot_passed_[slot] = 0;
    }
    const size_t unit_count = units.bounds.size();
    unit_first_phase_.assign(unit_count, 0);
    unit_passed_.assign(unit_count, 0);
    for (size_t u = 0; u < unit_count; ++u) {
        assert(units.slots[u] < units.slot_count);
        unit_first_phase_[u] = units.forced[u] || slot_passed_[units.slots[u]] + 1 == gpu_frame_;
    }
    entry_drawn_.assign(units.objects.size(), 0);
    for (size_t e = 0; e < units.objects.size(); ++e) {
        if (!unit_first_phase_[units.object_units[e]]) continue;
        entry_drawn_[e] = 1;
        drawObject(units.objects[e]);
    }
}

void DepthRasterDevice::drawSecondPhase(GpuTest test, PyramidBound shape) {
    const auto unit_count = static_cast<uint32_t>(units_.bounds.size());
    flags_.assign(unit_count, 1);
    const uint32_t one_batch[] = {unit_count};
    const std::span<const uint32_t> ends =
        units_.batch_ends.empty() ? std::span<const uint32_t>(one_batch) : units_.batch_ends;
    assert(ends.back() == unit_count);
    uint32_t first = 0;
    size_t entry = 0;  // the entries are in the order of their units
    for (const uint32_t end : ends) {
        assert(end >= first && end <= unit_count);
        const size_t count = end - first;
        if (test == GpuTest::Pyramid) {
            if (with_pyramid_) {
                build();
                testOnPyramid(units_.bounds.subspan(first, count), shape,
                              std::span<uint8_t>(flags_).subspan(first, count));
            }
        } else {
            for (uint32_t u = first; u < end; ++u) {
                flags_[u] = passingCells(units_.bounds[u]) > 0 ? 1 : 0;
            }
        }
        for (uint32_t u = first; u < end; ++u) {
            unit_passed_[u] = units_.forced[u] || flags_[u];
            if (unit_passed_[u]) slot_passed_[units_.slots[u]] = gpu_frame_;
        }
        for (; entry < units_.objects.size() && units_.object_units[entry] < end; ++entry) {
            if (entry_drawn_[entry] || !unit_passed_[units_.object_units[entry]]) continue;
            entry_drawn_[entry] = 1;
            drawObject(units_.objects[entry]);
        }
        first = end;
    }
    units_ = {};  // the culler's spans are not held beyond this call
}

void DepthRasterDevice::readResults(std::span<uint8_t> first_phase, std::span<uint8_t> passed) {
    assert(first_phase.size() == unit_first_phase_.size() && passed.size() == unit_passed_.size());
    std::copy(unit_first_phase_.begin(), unit_first_phase_.end(), first_phase.begin());
    std::copy(unit_passed_.begin(), unit_passed_.end(), passed.begin());
}

}  // namespace occsim
