// fc-scene: POV-Ray's shadow tests described to frame coherence, and run again
// (shadow_tests.h).

// frame.h must always be the first POV file included (pulls in platform config)
#include "backend/frame.h"

#include "backend/scene/objects.h"
#include "backend/scene/scene.h"
#include "backend/shape/isosurf.h"

#include "ray_flags.h"
#include "shadow_tests.h"

// this must be the last file included
#include "base/povdebug.h"

namespace povrayfc
{
namespace scene
{

namespace
{

// An object below `objects` whose interior has media or fades light, or an isosurface.
bool HoldsStatefulShadowWay(const std::vector<pov::ObjectPtr>& objects)
{
	for(pov::ObjectPtr object : objects)
	{
		if(dynamic_cast<const pov::IsoSurface *>(object) != nullptr)
			return true;
		const pov::Interior *interior = object->interior;
		if(interior != nullptr && (!interior->media.empty() || interior->Fade_Power > 0.0))
			return true;
		const pov::CompoundObject *compound = dynamic_cast<const pov::CompoundObject *>(object);
		if(compound != nullptr && HoldsStatefulShadowWay(compound->children))
			return true;
	}
	return false;
}

}  // namespace

bool ShadowTestsReplayable(const pov::SceneData& scene)
{
	return scene.fog == nullptr && scene.atmosphere.empty() && !scene.photonSettings.photonsEnabled &&
	       !scene.radiositySettings.radiosityEnabled && !scene.useSubsurface && !HoldsStatefulShadowWay(scene.objects);
}

void DescribeKeptShadowTest(ShadowSegmentRecord& record, const pov::LightSource& light, const pov::Ray& ray,
                            const pov::Trace::TraceTicket& ticket, const pov::SceneData& scene)
{
	// TraceShadowReplayer finds the light among the scene's lights by its index and makes
	// its ticket from the scene's settings.
	if(light.lightGroupLight || light.index > 0xffff || ticket.traceLevel > 0xff ||
	   ticket.adcBailout != scene.parsedAdcBailout || ticket.maxAllowedTraceLevel != scene.parsedMaxTraceLevel)
		return;
	record.Describe(std::uint16_t(light.index), RayFlagBits(ray), std::uint8_t(ticket.traceLevel));
}

bool TraceShadowReplayer::Replay(const ShadowTest& test, float colourOut[3], ShadowRun& run)
{
	if(test.light >= scene_.lightSources.size())
		return false;
	const pov::LightSource& light = *scene_.lightSources[test.light];
	if(light.index != test.light || light.lightGroupLight)
		return false;
	pov::Ray ray(test.origin, test.direction);
	if(SetRayFlagBits(ray, test.rayFlags) == false)
		return false;
	pov::Trace::TraceTicket ticket(scene_.parsedMaxTraceLevel, scene_.parsedAdcBailout, scene_.outputAlpha);
	ticket.traceLevel = test.traceLevel;
	pov::RGBColour colour(test.colourIn[0], test.colourIn[1], test.colourIn[2]);
	double depth = test.depth;
	bool cached;
	// The test's ShadowSegmentRecord writes what answered it into `run` (it records nothing now).
	detail::tlsShadowRun = &run;
	trace_.ReplayPointLightShadowRay(light, depth, ray, colour, ticket, cached);
	detail::tlsShadowRun = nullptr;
	run.cached = cached;
	// The loop takes off what it passes from the depth left (by more than SHADOW_TOLERANCE).
	run.passed = depth != test.depth;
	colourOut[0] = colour.red();
	colourOut[1] = colour.green();
	colourOut[2] = colour.blue();
	return true;
}

}  // namespace scene
}  // namespace povrayfc
