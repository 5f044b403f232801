// fc-scene: POV-Ray's scene-level searches described to frame coherence, and run again.
//
// A search for a ray's nearest intersection that ended in a tie (povray-fc's tie_watch.h)
// is kept with what it takes to run it again: its ray, POV-Ray's flags of the ray, which
// conditions it searched with (its kind), the depth it started from, and what it found. In a
// frame with a new order of the objects, the engine asks TraceTieReplayer to run it again
// through the same Trace::FindIntersection (tie_replay.h). Only the two searches whose
// conditions are known here are described: TraceRay's and the shadow loop's; any other
// leaves its tie undescribed, and its sample is traced again whenever the order changes.
#ifndef POVRAYFC_TIE_SEARCHES_H
#define POVRAYFC_TIE_SEARCHES_H

#include <cstdint>

#include "povrayfc/tie_replay.h"
#include "povrayfc/tie_watch.h"

namespace pov
{
class Ray;
class Intersection;
struct RayObjectCondition;
class Trace;
}

namespace povrayfc
{
namespace scene
{

// Made on the stack of Trace::FindIntersection, after its TieWatch: when it goes (the
// search done) and the search ended in a tie, describes it to the watch and tells it what
// `best` holds. Costs a thread-local test when no sample is being recorded, and a few
// stores and compares a search when one is.
class TieSearchHook
{
	public:
		TieSearchHook(const pov::Ray& ray, const pov::Intersection& best, const pov::RayObjectCondition& precondition,
		              const pov::RayObjectCondition& postcondition) :
			ray_(TieWatchOpen() ? &ray : NULL), best_(best), precondition_(precondition), postcondition_(postcondition) { }
		~TieSearchHook() { if(ray_ != NULL && TieSearchTied()) Describe(); }
	private:
		void Describe() const;
		const pov::Ray *ray_;  // null when no sample is being recorded
		const pov::Intersection& best_;
		const pov::RayObjectCondition& precondition_;
		const pov::RayObjectCondition& postcondition_;
		TieSearchHook(const TieSearchHook&);
		TieSearchHook& operator=(const TieSearchHook&);
};

// Runs a described search again through `trace` (the render thread's own tracer, in the
// frame it renders).
class TraceTieReplayer : public TieReplayer
{
	public:
		explicit TraceTieReplayer(pov::Trace& trace) : trace_(trace) { }
		virtual bool Replay(const TiedSearch& search, double& depth, std::uint32_t& unitIndex,
		                    std::uint64_t& objectHash);
	private:
		pov::Trace& trace_;
};

}  // namespace scene
}  // namespace povrayfc

#endif
