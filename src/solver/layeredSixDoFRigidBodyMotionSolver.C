/*---------------------------------------------------------------------------*\
    floatfoam: the six-DoF motion solver with a scale that depends on height alone.

    Type `layeredSixDoFRigidBodyMotion` (dynamicMeshDict's motionSolver); its coefficients are
    `sixDoFRigidBodyMotionCoeffs`, read by OpenFOAM v1912's sixDoFRigidBodyMotionSolver (the body,
    its mass, constraints and integrator, the state written to uniform/ for a restart). The
    base solver moves the body; this class then moves every mesh point as the body moves,
    scaled by

        s(z) = 1                                  for z_lo <= z <= z_hi,
        s(z) = (z - z_bottom)/(z_lo - z_bottom)   below the band,
        s(z) = (z_top - z)/(z_top - z_hi)         above it,

    with z taken at the mesh's initial points: [z_lo, z_hi] the body's height (its patches'
    points, widened about its middle by the optional `layerBandExpansion`, default 1, and held
    inside the mesh), z_bottom and z_top the mesh's lowest and highest points. For a body free
    in heave only, every row of points then moves as one: the rows stay horizontal, the cells
    beside the body translate without deforming and the tank's ends slide along themselves.
    interFoam's gravity term balances the pressure across horizontal faces only (floatfoam's
    docs/openfoam-v1912.md), which a scale that varies along a row would tilt.

    The base solver's own distance scale (`innerDistance`, `outerDistance`) is computed once at
    the start and not used: the motionScale field it writes then is not this motion's.
\*---------------------------------------------------------------------------*/

#include "sixDoFRigidBodyMotionSolver.H"
#include "addToRunTimeSelectionTable.H"
#include "polyMesh.H"

namespace Foam
{

class layeredSixDoFRigidBodyMotionSolver
:
    public sixDoFRigidBodyMotionSolver
{
    //- The scale of the body's motion at each point (s(z) above)
    scalarField layerScale_;

    //- s(z) at the mesh's initial points
    void computeLayerScale()
    {
        const pointField& p0 = points0();
        const labelHashSet bodyPatches
        (
            mesh().boundaryMesh().patchSet(coeffDict().get<wordRes>("patches"))
        );
        scalar bodyLo = GREAT;
        scalar bodyHi = -GREAT;
        for (const label patchi : bodyPatches)
        {
            for (const label pointi : mesh().boundaryMesh()[patchi].meshPoints())
            {
                bodyLo = min(bodyLo, p0[pointi].z());
                bodyHi = max(bodyHi, p0[pointi].z());
            }
        }
        reduce(bodyLo, minOp<scalar>());
        reduce(bodyHi, maxOp<scalar>());

        scalar bottom = GREAT;
        scalar top = -GREAT;
        forAll(p0, pointi)
        {
            bottom = min(bottom, p0[pointi].z());
            top = max(top, p0[pointi].z());
        }
        reduce(bottom, minOp<scalar>());
        reduce(top, maxOp<scalar>());

        if (bodyHi < bodyLo)
        {
            FatalErrorInFunction
                << "the body's patches have no points" << exit(FatalError);
        }

        const scalar expansion =
            coeffDict().lookupOrDefault<scalar>("layerBandExpansion", 1.0);
        const scalar middle = 0.5*(bodyLo + bodyHi);
        const scalar half = 0.5*(bodyHi - bodyLo)*expansion;
        // a thousandth of the mesh's height is kept between the band and its bottom and top
        const scalar room = 1e-3*(top - bottom);
        const scalar lo = max(middle - half, bottom + room);
        const scalar hi = min(middle + half, top - room);

        layerScale_.setSize(p0.size());
        forAll(p0, pointi)
        {
            const scalar z = p0[pointi].z();
            if (z < lo)
            {
                layerScale_[pointi] = max((z - bottom)/(lo - bottom), scalar(0));
            }
            else if (z > hi)
            {
                layerScale_[pointi] = max((top - z)/(top - hi), scalar(0));
            }
            else
            {
                layerScale_[pointi] = 1;
            }
        }

        Info<< "layeredSixDoFRigidBodyMotion: body rows z = " << lo << " to " << hi
            << ", mesh z = " << bottom << " to " << top << endl;
    }

public:

    TypeName("layeredSixDoFRigidBodyMotion");

    layeredSixDoFRigidBodyMotionSolver(const polyMesh& mesh, const IOdictionary& dict)
    :
        sixDoFRigidBodyMotionSolver(mesh, dict)
    {
        computeLayerScale();
    }

    virtual ~layeredSixDoFRigidBodyMotionSolver() = default;

    //- The base solver's step for the body, then every point moved by s(z)
    virtual void solve()
    {
        sixDoFRigidBodyMotionSolver::solve();
        // vertical and a function of the point's initial height alone: the same on every
        // processor that shares the point, in the plane of every wedge, empty or symmetry
        // patch, and along the tank's vertical ends, so no constraint is applied (a slip
        // condition would take its normals from the ends' patch and move points across it)
        pointDisplacement_.primitiveFieldRef() =
            motion().transform(points0(), layerScale_) - points0();
    }
};

defineTypeNameAndDebug(layeredSixDoFRigidBodyMotionSolver, 0);
addToRunTimeSelectionTable
(
    motionSolver,
    layeredSixDoFRigidBodyMotionSolver,
    dictionary
);

} // End namespace Foam
