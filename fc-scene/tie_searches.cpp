// fc-scene: POV-Ray's scene-level searches described to frame coherence, and run again
// (tie_searches.h).

// frame.h must always be the first POV file included (pulls in platform config)
#include "backend/frame.h"

#include <typeinfo>

#include "backend/render/trace.h"

#include "povrayfc/scene_signature.h"
#include "povrayfc/tie_watch.h"

#include "ray_flags.h"
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
