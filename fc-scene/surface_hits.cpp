// fc-scene: POV-Ray's surface hits described to frame coherence, and run again
// (surface_hits.h).

// frame.h must always be the first POV file included (pulls in platform config)
#include "backend/frame.h"

#include "backend/interior/interior.h"
#include "backend/pattern/pattern.h"
#include "backend/scene/objects.h"
#include "backend/scene/scene.h"
#include "backend/texture/normal.h"
#include "backend/texture/pigment.h"

#include "ray_flags.h"
#include "shadow_tests.h"
#include "surface_hits.h"

// this must be the last file included
#include "base/povdebug.h"

namespace povrayfc
{
namespace scene
{

namespace
{

void AddVector(SignatureHash& hash, const pov::Vector3d& v)
{
	hash.Add(v[pov::X]);
	hash.Add(v[pov::Y]);
	hash.Add(v[pov::Z]);
}

void AddColour(SignatureHash& hash, const pov::Colour& c)
{
	hash.Add(c.red());
	hash.Add(c.green());
	hash.Add(c.blue());
	hash.Add(c.filter());
	hash.Add(c.transm());
}

void AddRGB(SignatureHash& hash, const pov::RGBColour& c)
{
	hash.Add(c.red());
	hash.Add(c.green());
	hash.Add(c.blue());
}

// Every field of a finish, one by one (a struct's padding is no value).
void AddFinish(SignatureHash& hash, const pov::FINISH& f)
{
	const SNGL values[] = {f.Diffuse, f.DiffuseBack, f.RawDiffuse, f.RawDiffuseBack, f.Brilliance, f.Specular, f.Roughness,
	                       f.Phong, f.Phong_Size, f.Irid, f.Irid_Film_Thickness, f.Irid_Turb, f.Temp_Caustics, f.Temp_IOR,
	                       f.Temp_Dispersion, f.Temp_Refract, f.Reflect_Exp, f.Crand, f.Metallic, f.Reflection_Falloff,
	                       f.Reflect_Metallic};
	for(SNGL v : values)
		hash.Add(v);
	AddRGB(hash, f.Ambient);
	AddRGB(hash, f.Emission);
	AddRGB(hash, f.Reflection_Max);
	AddRGB(hash, f.Reflection_Min);
	AddRGB(hash, f.SubsurfaceTranslucency);
	AddRGB(hash, f.SubsurfaceAnisotropy);
	hash.Add(f.Reflection_Type);
	hash.Add(f.Conserve_Energy);
	hash.Add(f.UseSubsurface);
}

// The interior's values refraction and fading read; false for one with media or subsurface
// scattering (a signature does not describe them).
bool AddInterior(SignatureHash& hash, const pov::Interior *interior)
{
	hash.Add(interior != nullptr);
	if(interior == nullptr)
		return true;
	if(!interior->media.empty() || interior->subsurface)
		return false;
	hash.Add(interior->hollow);
	hash.Add(interior->Disp_NElems);
	const SNGL values[] = {interior->IOR, interior->Dispersion, interior->Caustics, interior->Old_Refract,
	                       interior->Fade_Distance, interior->Fade_Power};
	for(SNGL v : values)
		hash.Add(v);
	AddRGB(hash, interior->Fade_Colour);
	return true;
}

}  // namespace

bool SurfaceHitsReplayable(const pov::SceneData& scene)
{
	return ShadowTestsReplayable(scene) && scene.rainbow == nullptr;
}

bool SurfaceSignature(pov::TraceThreadData *threadData, const pov::Ray& ray, bool found,
                      const pov::Intersection& hit, std::uint64_t& signature)
{
	SignatureHash hash;
	// What the ray takes along: the interiors it is in (refraction and fading read them).
	hash.Add(ray.IsHollowRay());
	hash.Add(ray.GetInteriors().size());
	for(const pov::Interior *interior : ray.GetInteriors())
		if(!AddInterior(hash, interior))
			return false;
	hash.Add(found);
	if(!found)
	{
		signature = hash.Value();
		return true;
	}
	// What Trace::ComputeTextureColour does before it lights the surface, on a copy: the
	// normal and the patterns may write into the intersection.
	pov::Intersection isect(hit);
	const pov::ObjectBase *object = isect.Object;
	if(!object->LLights.empty() || Test_Flag(object, MULTITEXTURE_FLAG) ||
	   (object->Texture == nullptr && Test_Flag(object, CUTAWAY_TEXTURES_FLAG)))
		return false;
	pov::Vector3d rawnormal;
	isect.Object->Normal(*rawnormal, &isect, threadData);
	if(Test_Flag(object, INVERTED_FLAG))
		rawnormal = -rawnormal;
	const double normaldirection = dot(rawnormal, pov::Vector3d(ray.Direction));
	if(normaldirection > 0.0)
		rawnormal = -rawnormal;
	pov::Assign_Vector(isect.INormal, *rawnormal);
	pov::Assign_Vector(isect.PNormal, *rawnormal);
	pov::Vector3d ipoint(isect.IPoint);
	if(Test_Flag(object, UV_FLAG))
	{
		pov::Vector2d uvcoords;
		isect.Object->UVCoord(*uvcoords, &isect, threadData);
		pov::Assign_UV_Vect(isect.Iuv, *uvcoords);
		ipoint = pov::Vector3d(uvcoords.u(), uvcoords.v(), 0.0);
	}
	hash.Add(isect.Depth);
	AddVector(hash, pov::Vector3d(isect.IPoint));
	AddVector(hash, rawnormal);
	AddVector(hash, ipoint);
	hash.Add(normaldirection > 0.0);
	hash.Add(object->Flags);
	if(!AddInterior(hash, object->interior))
		return false;
	// Whether the ray leaves the object or enters it (refraction and fading ask the ray).
	hash.Add(object->interior != nullptr && ray.IsInterior(object->interior));

	const pov::TEXTURE *texture =
		(normaldirection > 0.0 && object->Interior_Texture != nullptr) ? object->Interior_Texture : object->Texture;
	hash.Add(texture != nullptr);
	if(texture != nullptr)
	{
		// Trace::ComputeOneTextureColour lights a plain texture's layers (ComputeLightedTexture).
		if(texture->Type != pov::PLAIN_PATTERN)
			return false;
		for(const pov::TEXTURE *layer = texture; layer != nullptr; layer = reinterpret_cast<const pov::TEXTURE *>(layer->Next))
		{
			if(layer->Pigment == nullptr || layer->Finish == nullptr)
				return false;
			pov::Colour colour;
			hash.Add(pov::Compute_Pigment(colour, layer->Pigment, *ipoint, &isect, &ray, threadData));
			AddColour(hash, colour);
			AddColour(hash, layer->Pigment->Quick_Colour);
			hash.Add(layer->Tnormal != nullptr);
			if(layer->Tnormal != nullptr)
			{
				pov::Vector3d normal(rawnormal);
				pov::Perturb_Normal(*normal, layer->Tnormal, *ipoint, &isect, &ray, threadData);
				if(Test_Flag(layer->Tnormal, DONT_SCALE_BUMPS_FLAG))
					normal.normalize();
				AddVector(hash, normal);
			}
			AddFinish(hash, *layer->Finish);
		}
	}
	signature = hash.Value();
	return true;
}

void DescribeSurfaceHit(pov::TraceThreadData *threadData, const pov::Ray& ray, bool found,
                        const pov::Intersection& isect, double maxDepth)
{
	if((!ray.GetInteriors().empty() && !ray.IsPrimaryRay()) || ray.IsMonochromaticRay() || ray.IsPhotonRay() ||
	   ray.IsRadiosityRay() || ray.IsShadowTestRay() || ray.IsSubsurfaceRay())
		return;
	SurfaceHit hit;
	hit.rayFlags = RayFlagBits(ray);
	for(int i = 0; i < 3; ++i)
	{
		hit.origin[i] = ray.Origin[i];
		hit.direction[i] = ray.Direction[i];
	}
	hit.maxDepth = maxDepth;
	if(SurfaceSignature(threadData, ray, found, isect, hit.signature))
		RecordSurfaceHit(hit);
}

bool TraceSurfaceReplayer::Replay(const SurfaceHit& hit, std::uint64_t& signature, std::uint32_t& unitIndex)
{
	pov::Ray ray(hit.origin, hit.direction);
	if(SetRayFlagBits(ray, hit.rayFlags) == false)
		return false;
	if(ray.IsPrimaryRay())
		trace_.AppendContainingInteriors(ray);
	return trace_.ReplaySurfaceHit(ray, hit.maxDepth, signature, unitIndex);
}

}  // namespace scene
}  // namespace povrayfc
