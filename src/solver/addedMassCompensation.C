/*---------------------------------------------------------------------------*\
    floatfoam: added-mass compensation of the body-fluid coupling, as a six-DoF restraint.

    Type `addedMassCompensation` (a restraint of sixDoFRigidBodyMotionCoeffs). interFoam
    moves the body at each outer corrector with the fluid's force of the corrector before, and
    the fluid answers a change of the body's acceleration within the step with an added mass:
    a body light beside it makes the correctors diverge (floatfoam's docs/coupling.md). With a
    compensating mass A (a 6 x 6 matrix over x, y, z and the rotations about x, y and z, in
    earth axes, about the centre of rotation, given as four tensors: `linear`, the force of a
    linear acceleration; `linearAngular`, the force of an angular one; `angularLinear` and
    `angular`, the moments of each), the restraint
    makes the generalized acceleration of the corrector

        q = (M + A)^-1 (F + A q_last)

    (M the body's mass and inertia in earth axes, F the force and moment on it, q_last the
    acceleration the corrector before took): the same acceleration once the correctors agree
    (q = q_last: M q = F), reached in one corrector where A is the fluid's answer. It returns
    the force and moment M q - F, at the centre of rotation. q_last is the acceleration this
    restraint gave (v1912 relaxes the acceleration after the restraints: with
    accelerationRelaxation below 1 the body took less of it); the first corrector of a run,
    and of a run resumed, is not compensated. With one corrector a step the compensation
    blends the step's acceleration with the last step's, as a relaxation does.
\*---------------------------------------------------------------------------*/

#include "sixDoFRigidBodyMotionRestraint.H"
#include "sixDoFRigidBodyMotion.H"
#include "addToRunTimeSelectionTable.H"

namespace Foam
{
namespace sixDoFRigidBodyMotionRestraints
{

class addedMassCompensation
:
    public sixDoFRigidBodyMotionRestraint
{
    //- The compensating mass's blocks: force of linear and of angular acceleration, moment of
    //  linear and of angular acceleration
    tensor linear_, linearAngular_, angularLinear_, angular_;

    //- The compensating mass, row by row
    FixedList<scalar, 36> addedMass_;

    //- Whether a corrector has taken an acceleration yet
    mutable bool started_;

    //- The acceleration the corrector before took: x, y, z, rotations about x, y, z
    mutable FixedList<scalar, 6> last_;

    //- x = a^-1 b by Gaussian elimination with partial pivoting (a: 6 x 6, row by row)
    static FixedList<scalar, 6> solve(FixedList<scalar, 36> a, FixedList<scalar, 6> b)
    {
        for (label k = 0; k < 6; ++k)
        {
            label pivot = k;
            for (label i = k + 1; i < 6; ++i)
            {
                if (mag(a[6*i + k]) > mag(a[6*pivot + k]))
                {
                    pivot = i;
                }
            }
            if (pivot != k)
            {
                for (label j = 0; j < 6; ++j)
                {
                    Swap(a[6*k + j], a[6*pivot + j]);
                }
                Swap(b[k], b[pivot]);
            }
            for (label i = k + 1; i < 6; ++i)
            {
                const scalar f = a[6*i + k]/a[6*k + k];
                for (label j = k; j < 6; ++j)
                {
                    a[6*i + j] -= f*a[6*k + j];
                }
                b[i] -= f*b[k];
            }
        }
        FixedList<scalar, 6> x;
        for (label i = 5; i >= 0; --i)
        {
            scalar s = b[i];
            for (label j = i + 1; j < 6; ++j)
            {
                s -= a[6*i + j]*x[j];
            }
            x[i] = s/a[6*i + i];
        }
        return x;
    }

public:

    TypeName("addedMassCompensation");

    addedMassCompensation(const word& name, const dictionary& dict)
    :
        sixDoFRigidBodyMotionRestraint(name, dict),
        linear_(Zero),
        linearAngular_(Zero),
        angularLinear_(Zero),
        angular_(Zero),
        addedMass_(Zero),
        started_(false),
        last_(Zero)
    {
        read(dict);
    }

    virtual autoPtr<sixDoFRigidBodyMotionRestraint> clone() const
    {
        return autoPtr<sixDoFRigidBodyMotionRestraint>(new addedMassCompensation(*this));
    }

    virtual ~addedMassCompensation() = default;

    virtual void restrain
    (
        const sixDoFRigidBodyMotion& motion,
        vector& restraintPosition,
        vector& restraintForce,
        vector& restraintMoment
    ) const
    {
        const tensor& Q = motion.orientation();
        const vector force = motion.mass()*motion.state().a();
        const vector moment = Q & motion.state().tau();  // the torque, in earth axes
        const diagTensor& I = motion.momentOfInertia();  // in the body's axes
        const tensor inertia =
            Q & tensor(I.xx(), 0, 0, 0, I.yy(), 0, 0, 0, I.zz()) & Q.T();

        FixedList<scalar, 36> mass(Zero);
        FixedList<scalar, 6> load;
        for (direction i = 0; i < 3; ++i)
        {
            mass[6*i + i] = motion.mass();
            load[i] = force[i];
            load[3 + i] = moment[i];
            for (direction j = 0; j < 3; ++j)
            {
                mass[6*(3 + i) + 3 + j] = inertia(i, j);
            }
        }
        if (!started_)  // no corrector before: the acceleration of the force alone
        {
            last_ = solve(mass, load);
            started_ = true;
        }
        FixedList<scalar, 36> total(mass);
        FixedList<scalar, 6> rhs(load);
        for (label i = 0; i < 6; ++i)
        {
            for (label j = 0; j < 6; ++j)
            {
                total[6*i + j] += addedMass_[6*i + j];
                rhs[i] += addedMass_[6*i + j]*last_[j];
            }
        }
        last_ = solve(total, rhs);
        FixedList<scalar, 6> restraint;
        for (label i = 0; i < 6; ++i)
        {
            scalar s = -load[i];
            for (label j = 0; j < 6; ++j)
            {
                s += mass[6*i + j]*last_[j];
            }
            restraint[i] = s;
        }
        restraintPosition = motion.centreOfRotation();
        restraintForce = vector(restraint[0], restraint[1], restraint[2]);
        restraintMoment = vector(restraint[3], restraint[4], restraint[5]);
        if (motion.report())
        {
            Info<< " force " << restraintForce << " moment " << restraintMoment << endl;
        }
    }

    virtual bool read(const dictionary& dict)
    {
        sixDoFRigidBodyMotionRestraint::read(dict);
        sDoFRBMRCoeffs_.readEntry("linear", linear_);
        sDoFRBMRCoeffs_.readEntry("linearAngular", linearAngular_);
        sDoFRBMRCoeffs_.readEntry("angularLinear", angularLinear_);
        sDoFRBMRCoeffs_.readEntry("angular", angular_);
        const tensor* blocks[2][2] =
            {{&linear_, &linearAngular_}, {&angularLinear_, &angular_}};
        for (label i = 0; i < 6; ++i)
        {
            for (label j = 0; j < 6; ++j)
            {
                addedMass_[6*i + j] = (*blocks[i/3][j/3])(i % 3, j % 3);
            }
        }
        return true;
    }

    virtual void write(Ostream& os) const
    {
        os.writeEntry("linear", linear_);
        os.writeEntry("linearAngular", linearAngular_);
        os.writeEntry("angularLinear", angularLinear_);
        os.writeEntry("angular", angular_);
    }
};

defineTypeNameAndDebug(addedMassCompensation, 0);
addToRunTimeSelectionTable
(
    sixDoFRigidBodyMotionRestraint,
    addedMassCompensation,
    dictionary
);

} // End namespace sixDoFRigidBodyMotionRestraints
} // End namespace Foam
