/*---------------------------------------------------------------------------*\
    floatfoam: the velocity of a rigid body's wall at the end of the step.

    Type `bodyVelocity` (a velocity boundary condition of the body's patch). Each face takes
    the velocity of the six-DoF body at its centre, v + omega x (x - centre of rotation), in
    the state the body has reached for the end of the step: from the mesh's motion solver
    (dynamicMeshDict: sixDoFRigidBodyMotion or floatfoam's layeredSixDoFRigidBodyMotion), or
    from the patch's point-displacement condition bodySixDoFRigidBodyDisplacement (the
    Laplacian's: v1912's sixDoFRigidBodyDisplacement with an accessor, compiled by
    scripts/build_solver.sh). Until the mesh moves (a body held still, or a restart before its
    first motion) it keeps the value it has, as movingWallVelocity does.
\*---------------------------------------------------------------------------*/

#include "fixedValueFvPatchFields.H"
#include "addToRunTimeSelectionTable.H"
#include "volFields.H"
#include "bodyMotion.H"

namespace Foam
{

class bodyVelocityFvPatchVectorField
:
    public fixedValueFvPatchVectorField
{
    //- The six-DoF motion of the body: the mesh's motion solver's, or the body patch's
    //  point-displacement condition's
    const sixDoFRigidBodyMotion& bodyMotion() const
    {
        const sixDoFRigidBodyMotion* motion =
            floatfoamBodyMotion(internalField().mesh(), patch().index());
        if (!motion)
        {
            FatalErrorInFunction
                << "bodyVelocity on patch " << patch().name() << " needs a six-DoF motion solver"
                << " in dynamicMeshDict or the point displacement bodySixDoFRigidBodyDisplacement"
                << " on the patch" << exit(FatalError);
        }
        return *motion;
    }

public:

    TypeName("bodyVelocity");

    bodyVelocityFvPatchVectorField
    (
        const fvPatch& p,
        const DimensionedField<vector, volMesh>& iF
    )
    :
        fixedValueFvPatchVectorField(p, iF)
    {}

    bodyVelocityFvPatchVectorField
    (
        const fvPatch& p,
        const DimensionedField<vector, volMesh>& iF,
        const dictionary& dict
    )
    :
        fixedValueFvPatchVectorField(p, iF, dict)
    {}

    bodyVelocityFvPatchVectorField
    (
        const bodyVelocityFvPatchVectorField& ptf,
        const fvPatch& p,
        const DimensionedField<vector, volMesh>& iF,
        const fvPatchFieldMapper& mapper
    )
    :
        fixedValueFvPatchVectorField(ptf, p, iF, mapper)
    {}

    bodyVelocityFvPatchVectorField(const bodyVelocityFvPatchVectorField& ptf)
    :
        fixedValueFvPatchVectorField(ptf)
    {}

    bodyVelocityFvPatchVectorField
    (
        const bodyVelocityFvPatchVectorField& ptf,
        const DimensionedField<vector, volMesh>& iF
    )
    :
        fixedValueFvPatchVectorField(ptf, iF)
    {}

    virtual tmp<fvPatchVectorField> clone() const
    {
        return tmp<fvPatchVectorField>(new bodyVelocityFvPatchVectorField(*this));
    }

    virtual tmp<fvPatchVectorField> clone
    (
        const DimensionedField<vector, volMesh>& iF
    ) const
    {
        return tmp<fvPatchVectorField>(new bodyVelocityFvPatchVectorField(*this, iF));
    }

    virtual void updateCoeffs()
    {
        if (updated())
        {
            return;
        }
        if (!internalField().mesh().moving())  // not moved yet, or a body held still
        {
            fixedValueFvPatchVectorField::updateCoeffs();
            return;
        }
        const sixDoFRigidBodyMotion& motion = bodyMotion();
        const vectorField& Cf = patch().Cf();
        vectorField Up(Cf.size());
        forAll(Cf, facei)
        {
            Up[facei] = motion.velocity(Cf[facei]);
        }
        vectorField::operator=(Up);
        fixedValueFvPatchVectorField::updateCoeffs();
    }

    virtual void write(Ostream& os) const
    {
        fvPatchVectorField::write(os);
        writeEntry("value", os);
    }
};

makePatchTypeField(fvPatchVectorField, bodyVelocityFvPatchVectorField);

} // End namespace Foam
