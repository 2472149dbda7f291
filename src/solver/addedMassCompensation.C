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

        q = (M + 2A)^-1 (F + A (q_last + q_step))

    (M the body's mass and inertia in earth axes, F the force and moment on it, q_last the
    acceleration the corrector before took, q_step the acceleration the last step ended with)
    and returns the force and moment M q - F, at the centre of rotation. Once the correctors
    agree (q = q_last) the body moves as

        M q = F - A (q - q_step)

    which is the coupling's two corrections with A = A_inf/2 (A_inf the added mass at infinite
    frequency): the compensation, (M + A)^-1 (F + A q_last), reaches in one corrector what the
    fluid's answer A would need many for (a body light beside its added mass makes the plain
    correctors diverge); and the lag correction, -A (q - q_step): the body's faces move with
    the step's velocity, so the fluid's pressure answers the mean of the step's two
    accelerations, A_inf (q + q_step)/2, where the body's equation wants A_inf q at the step's
    end (floatfoam's docs/coupling.md and docs/studies/time-step.md). A step is the Time's time
    index. q_last is the acceleration this restraint gave (v1912 relaxes the acceleration after
    the restraints: with accelerationRelaxation below 1 the body took less of it). The first
    corrector of a run takes q_last as the acceleration of the force alone, and q_step as the
    state's: zero on a release from rest (time 0, the acceleration v1912's Newmark integrator
    starts from), and the acceleration of the force alone on a run resumed or restarted.
\*---------------------------------------------------------------------------*/

#include "sixDoFRigidBodyMotionRestraint.H"
#include "sixDoFRigidBodyMotion.H"
#include "addToRunTimeSelectionTable.H"
#include "Time.H"

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

    //- The time index of the step the last corrector was of, and the acceleration the step
    //  before it ended with
    mutable label step_;
    mutable FixedList<scalar, 6> stepStart_;

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
        last_(Zero),
        step_(-1),
        stepStart_(Zero)
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
        const Time& time = motion.time();
        if (!started_)  // no corrector before: the acceleration of the force alone
        {
            last_ = solve(mass, load);
            started_ = true;
            step_ = time.timeIndex();
            const bool released = time.startTime().value() <= 0.5*time.deltaTValue();
            stepStart_ = released ? FixedList<scalar, 6>(Zero) : last_;
        }
        else if (time.timeIndex() != step_)  // the step's first corrector
        {
            step_ = time.timeIndex();
            stepStart_ = last_;
        }
        FixedList<scalar, 36> total(mass);
        FixedList<scalar, 6> rhs(load);
        for (label i = 0; i < 6; ++i)
        {
            for (label j = 0; j < 6; ++j)
            {
                total[6*i + j] += 2*addedMass_[6*i + j];
                rhs[i] += addedMass_[6*i + j]*(last_[j] + stepStart_[j]);
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
