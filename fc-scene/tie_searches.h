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

// POV-Ray's Ray and Intersection (frame.h is always the first POV-Ray header included)
#include "backend/frame.h"

#include "povrayfc/tie_replay.h"
#include "povrayfc/tie_watch.h"

namespace pov
{
class Trace;
}

namespace povrayfc
{
namespace scene
{

// The TieWatch of Trace::FindIntersection with conditions: if the search ends in a tie,
// the watch asks it what the search was (TieDescriber). It keeps what it reads for that
// only while recording; otherwise it costs what a TieWatch costs.
class SearchTieWatch
{
	public:
		SearchTieWatch(const pov::Ray& ray, const pov::Intersection& best, const pov::RayObjectCondition& precondition,
		               const pov::RayObjectCondition& postcondition) :
			watch_(ray.Direction, best.Depth, &Describe, this)
		{
			if(watch_.Recording() == false)
				return;
			ray_ = &ray;
			best_ = &best;
			precondition_ = &precondition;
			postcondition_ = &postcondition;
		}
	private:
		static bool Describe(const void *self, TiedSearch& search, std::uint32_t& unitIndex);
		TieWatch watch_;  // asks Describe only while recording, when the rest is set
		const pov::Ray *ray_;
		const pov::Intersection *best_;
		const pov::RayObjectCondition *precondition_;
		const pov::RayObjectCondition *postcondition_;
		SearchTieWatch(const SearchTieWatch&);
		SearchTieWatch& operator=(const SearchTieWatch&);
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
