// fc-scene: POV-Ray's scene-level searches described to frame coherence, and run again
// (tie_searches.h).

// frame.h must always be the first POV file included (pulls in platform config)
#include "backend/frame.h"

#include <typeinfo>

#include "backend/render/trace.h"

#include "povrayfc/scene_signature.h"
#include "povrayfc/tie_watch.h"

#include "tie_searches.h"

// this must be the last file included
#include "base/povdebug.h"

namespace povrayfc
{
namespace scene
{

using pov::Intersection;
using pov::Ray;
using pov::RayObjectCondition;

namespace
{

// The kinds of search fc can run again: the conditions each searched with.
enum : std::uint8_t
{
	kUnknownSearch = 0,
	kTraceRaySearch = 1,    // TraceRay: NoSomethingFlagRayObjectCondition, TrueRayObjectCondition
	kShadowRaySearch = 2    // the shadow loop: NoShadowFlagRayObjectCondition, SmallToleranceRayObjectCondition
};

// Exactly these types: a subclass could decide otherwise.
std::uint8_t SearchKind(const RayObjectCondition& precondition, const RayObjectCondition& postcondition)
{
	if(typeid(precondition) == typeid(pov::NoSomethingFlagRayObjectCondition) &&
	   typeid(postcondition) == typeid(pov::TrueRayObjectCondition))
		return kTraceRaySearch;
	if(typeid(precondition) == typeid(pov::NoShadowFlagRayObjectCondition) &&
	   typeid(postcondition) == typeid(pov::SmallToleranceRayObjectCondition))
		return kShadowRaySearch;
	return kUnknownSearch;
}

// The ray's flags a search or an object's intersection may read. Not the hollow flag: it
// follows the ray's interiors, which no search reads (nor are they kept).
enum : std::uint16_t
{
	kPrimary = 1, kReflection = 2, kRefraction = 4, kSubsurface = 8, kShadowTest = 16,
	kPhoton = 32, kRadiosity = 64, kMonochromatic = 128, kPretrace = 256
};

std::uint16_t RayFlagBits(const Ray& ray)
{
	return std::uint16_t((ray.IsPrimaryRay() ? kPrimary : 0) | (ray.IsReflectionRay() ? kReflection : 0) |
	                     (ray.IsRefractionRay() ? kRefraction : 0) | (ray.IsSubsurfaceRay() ? kSubsurface : 0) |
	                     (ray.IsShadowTestRay() ? kShadowTest : 0) | (ray.IsPhotonRay() ? kPhoton : 0) |
	                     (ray.IsRadiosityRay() ? kRadiosity : 0) | (ray.IsMonochromaticRay() ? kMonochromatic : 0) |
	                     (ray.IsPretraceRay() ? kPretrace : 0));
}

// Gives `ray` the flags `bits` through Ray's own setters; false when they cannot make them.
bool SetRayFlagBits(Ray& ray, std::uint16_t bits)
{
	const bool shadowTest = (bits & kShadowTest) != 0, photon = (bits & kPhoton) != 0;
	const bool radiosity = (bits & kRadiosity) != 0, monochromatic = (bits & kMonochromatic) != 0;
	const bool pretrace = (bits & kPretrace) != 0;
	if((bits & (kReflection | kRefraction)) == (kReflection | kRefraction))
	{
		// A ray reflected inside a refracted one carries both (Ray::SetFlags from a parent).
		const Ray parent(Ray::RefractionRay, shadowTest, photon, radiosity, monochromatic, pretrace);
		ray.SetFlags(Ray::ReflectionRay, parent);
	}
	else
	{
		const Ray::RayType type = (bits & kPrimary) ? Ray::PrimaryRay : (bits & kReflection) ? Ray::ReflectionRay :
		                          (bits & kRefraction) ? Ray::RefractionRay : (bits & kSubsurface) ? Ray::SubsurfaceRay :
		                          Ray::OtherRay;
		ray.SetFlags(type, shadowTest, photon, radiosity, monochromatic, pretrace);
	}
	return RayFlagBits(ray) == bits;
}

}  // namespace

bool SearchTieWatch::Describe(const void *context, TiedSearch& search, std::uint32_t& unitIndex)
{
	const SearchTieWatch& self = *static_cast<const SearchTieWatch *>(context);
	// Another kind of search stays undescribed: its sample is traced again.
	search.kind = SearchKind(*self.precondition_, *self.postcondition_);
	if(search.kind == kUnknownSearch)
		return false;
	search.rayFlags = RayFlagBits(*self.ray_);
	for(int i = 0; i < 3; i++)
		search.origin[i] = self.ray_->Origin[i];
	// Which object the search found, if any: both searches start with none (TraceRay's
	// intersection is new; the shadow loop clears it before each search), and
	// FindIntersection sets it with the depth.
	const pov::ObjectBase *object = self.best_->Object;
	unitIndex = (object != NULL) ? object->fcUnit : kUnitNothing;
	search.objectHash = (object != NULL) ? object->fcHash : 0;
	return true;
}

bool TraceTieReplayer::Replay(const TiedSearch& search, double& depth, std::uint32_t& unitIndex,
                              std::uint64_t& objectHash)
{
	Ray ray(search.origin, search.direction);
	if(SetRayFlagBits(ray, search.rayFlags) == false)
		return false;
	Intersection best;  // no object, as both searches start
	best.Depth = search.start;
	switch(search.kind)
	{
		case kTraceRaySearch:
		{
			pov::NoSomethingFlagRayObjectCondition precondition;
			pov::TrueRayObjectCondition postcondition;
			trace_.FindIntersection(best, ray, precondition, postcondition);
			break;
		}
		case kShadowRaySearch:
		{
			pov::NoShadowFlagRayObjectCondition precondition;
			pov::SmallToleranceRayObjectCondition postcondition;
			trace_.FindIntersection(best, ray, precondition, postcondition);
			break;
		}
		default:
			return false;
	}
	depth = best.Depth;
	unitIndex = (best.Object != NULL) ? best.Object->fcUnit : kUnitNothing;
	objectHash = (best.Object != NULL) ? best.Object->fcHash : 0;
	return true;
}

}  // namespace scene
}  // namespace povrayfc
