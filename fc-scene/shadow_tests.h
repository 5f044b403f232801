// fc-scene: POV-Ray's shadow tests described to frame coherence, and run again.
//
// A shadow test that passed something letting light through is kept with its sample when
// the scene's shadow tests can be run again (ShadowTestsReplayable): with its ray, the
// light's index, the ray's flags, the trace level, and the light's colour before and after
// it (ShadowSegmentRecord::LightColour and DescribeShadowTest, from
// Trace::TracePointLightShadowRay). In a frame where only such
// tests of a sample meet a change, the engine asks TraceShadowReplayer to run them again
// through the same Trace::TracePointLightShadowRay (povray-fc's shadow_replay.h says why
// that is exact).
#ifndef POVRAYFC_SHADOW_TESTS_H
#define POVRAYFC_SHADOW_TESTS_H

// frame.h is always the first POV-Ray header included
#include "backend/frame.h"
#include "backend/render/trace.h"

#include "povrayfc/ray_recording.h"
#include "povrayfc/shadow_replay.h"

namespace pov
{
class SceneData;
}

namespace povrayfc
{
namespace scene
{

// Whether a shadow test of the scene reads no thread state but the shadow caches, and no
// state of its ray but what a ShadowTest keeps: no media, fog, photons, radiosity or
// subsurface scattering, no interior that fades light (the ray's interiors would count),
// and no isosurface (its root finder keeps the last root-free stretch from ray to ray).
bool ShadowTestsReplayable(const pov::SceneData& scene);

// As a test ends: tells `record` what the test took besides its ray and the light's colour,
// when it wants to know (it passed something, and its sample keeps such tests). A light of
// a light group, a ticket other than the scene's, or a trace level past 255 is not kept.
void DescribeKeptShadowTest(ShadowSegmentRecord& record, const pov::LightSource& light, const pov::Ray& ray,
                            const pov::Trace::TraceTicket& ticket, const pov::SceneData& scene);
inline void DescribeShadowTest(ShadowSegmentRecord& record, const pov::LightSource& light, const pov::Ray& ray,
                               const pov::Trace::TraceTicket& ticket, const pov::SceneData& scene)
{
	if(record.Wanted())
		DescribeKeptShadowTest(record, light, ray, ticket, scene);
}

// Runs a kept shadow test again through `trace` (the render thread's own tracer, in the
// frame it renders), with the shadow caches empty as the test found them.
class TraceShadowReplayer : public ShadowReplayer
{
	public:
		TraceShadowReplayer(pov::Trace& trace, const pov::SceneData& scene) : trace_(trace), scene_(scene) { }
		virtual bool Replay(const ShadowTest& test, float colourOut[3], ShadowRun& run);
	private:
		pov::Trace& trace_;
		const pov::SceneData& scene_;
};

}  // namespace scene
}  // namespace povrayfc

#endif
