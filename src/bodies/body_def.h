// A body made from its definition (Box2D v3's defs): the definition is checked at the API boundary,
// with an error that names the body and the field, and turned into the body's record and state
// (mass, centre of mass and inertia from the shape at uniform density, lecture: "barycenter and
// moment of inertia assuming uniform density").
#pragma once

#include <collide/body.h>

#include "bodies/body_storage.h"

#include <string>
#include <vector>

namespace collide::detail {

// True when the inertia is a multiple of the identity (to float precision), where the gyroscopic
// term w x (I w) vanishes (BodyRecord::isotropicInertia).
bool isIsotropic(const Mat3& inertia);

// The name errors give the body: `body "crate"`, or `body` when it has none.
std::string bodyLabel(const BodyDef& def);

// Throws Error, prefixed with the body's label, for a definition no body can be made from.
void validateBodyDef(const BodyDef& def);

// Throws Error, prefixed with `who` ("body \"crate\": parts[2]"), for a part no body of this type
// can have.
void validatePartDef(const PartDef& part, BodyType type, const std::string& who);
PartRecord makePartRecord(const PartDef& part);
Compound::Child makePartChild(const PartDef& part);

// Gives a body made of parts its parts (at creation, World::addPart, removePart): the compound shape,
// the part records and the record's summaries of them, the mass properties (dynamic bodies: from
// the parts' densities, scaled to BodyRecord::givenMass if set), the radii and extent. The body's
// origin stays where it is and its velocity field is kept. Throws Error (and changes nothing) when
// they cannot be computed; at least one child.
void setBodyParts(BodyRecord& record, BodyState& state, Array<Compound::Child> children,
                  Array<PartRecord> parts);

// Changes a body's type (World::setType): mass properties from its shape or parts for a dynamic body
// (its density, or BodyDef::mass if given), none for the others; the origin and the velocity field
// kept, a static body stopped. Throws Error, changing nothing, for a type the body cannot have (a
// plane or an open mesh made dynamic, a particle made anything else).
void setBodyType(BodyRecord& record, BodyState& state, BodyType type);

// Fills a freshly allocated slot from a valid definition. Throws Error (prefixed with the body's
// label) when the shape's mass properties or bounds are not representable at this scale and place.
void initBody(const BodyDef& def, BodyRecord& record, BodyState& state);

// Throws Error (prefixed with `who`) when the body's box at its pose is not representable in float
// or its shape's reach is not (initBody's last test; World::setTransform and setBodyParts run it on
// their copies before they change anything).
void requireRepresentableBounds(const BodyRecord& record, const BodyState& state, const std::string& who);

}  // namespace collide::detail
