// fc-scene: POV-Ray's surface hits described to frame coherence, and run again.
//
// A sample traced again because a change reached it keeps its first rays' hits
// (povray-fc's surface_replay.h), in scenes where a hit can be run again
// (SurfaceHitsReplayable): the ray (origin, direction, flags, maximum depth) and a signature
// of what the trace reads of the hit (SurfaceSignature), from Trace::TraceRay right after its
// search. In a frame where only such hits of a sample meet a change, the engine asks
// TraceSurfaceReplayer to run the same search again (Trace::ReplaySurfaceHit) and compares
// signatures (surface_replay.h says why that is exact).
#ifndef POVRAYFC_SURFACE_HITS_H
#define POVRAYFC_SURFACE_HITS_H

#include <cstdint>

// frame.h is always the first POV-Ray header included
#include "backend/frame.h"
#include "backend/render/trace.h"
#include "backend/render/tracepixel.h"

#include "povrayfc/ray_recording.h"
#include "povrayfc/surface_replay.h"

namespace pov
{
class SceneData;
class TraceThreadData;
}

namespace povrayfc
{
namespace scene
{

// Whether a hit of the scene can be run again and reads no thread state: as for shadow
// tests (shadow_tests.h: no media, fog, photons, radiosity, subsurface, fading interior or
// isosurface), and no rainbow.
bool SurfaceHitsReplayable(const pov::SceneData& scene);

// Everything Trace::ComputeTextureColour and what it calls read of the hit `isect` of `ray`
// (found: whether the search found one) but the lights, in one hash: the interiors the ray
// is in, the depth, the point, the raw normal as the trace turns it, the uv coordinates, the
// object's flags, each texture layer's pigment colour, bent normal and finish, and the
// interior. Computed on a copy of `isect`. False when the hit is not one a signature
// describes: several textures, texture maps, light groups, an interior with media or
// subsurface scattering.
bool SurfaceSignature(pov::TraceThreadData *threadData, const pov::Ray& ray, bool found,
                      const pov::Intersection& isect, std::uint64_t& signature);

// Right after Trace::TraceRay's search, when the sample keeps its hits (RecordRaySegment said so):
// the hit, described and recorded. A ray inside an object is kept only when it is a camera
// ray (run again, it gets the interiors its origin is in as a camera ray does); nor is one
// with a spectral band, photon, radiosity, shadow or subsurface flag.
void DescribeSurfaceHit(pov::TraceThreadData *threadData, const pov::Ray& ray, bool found,
                        const pov::Intersection& isect, double maxDepth);

// Runs a kept hit's search again through `trace` (the render thread's own tracer, in the
// frame it renders).
class TraceSurfaceReplayer : public SurfaceReplayer
{
	public:
		explicit TraceSurfaceReplayer(pov::TracePixel& trace) : trace_(trace) { }
		virtual bool Replay(const SurfaceHit& hit, std::uint64_t& signature, std::uint32_t& unitIndex);
	private:
		pov::TracePixel& trace_;
};

}  // namespace scene
}  // namespace povrayfc

#endif
