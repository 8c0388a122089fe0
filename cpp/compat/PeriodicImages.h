// Points of a periodic domain and their images a whole period away. A cell's own mesh may
// reach across a periodic side (its patch is wrapped, compat/Patch.h): its nodes there lie
// beyond the domain, a period from the shared mesh's nodes at the same place. Transfers
// between the meshes locate each point at the image that lies in the mesh it is taken from.
#pragma once
#include <array>
#include <span>

namespace cellphase::compat
{
/// Axis-aligned box: lower corner, then upper corner.
using Box = std::array<double, 6>;

/// The domain's period along each axis, 0 where it is not periodic. Set once, from the
/// scene, before any mesh is built (all zero until then: no images).
void set_periods(const std::array<double, 3>& periods);
const std::array<double, 3>& periods();
bool any_periodic();

/// Each point (rows of 3) that lies outside `box` along a periodic axis but has an image
/// inside it (within round-off of the period) is moved to that image.
void move_into(std::span<double> points, const Box& box);
} // namespace cellphase::compat
