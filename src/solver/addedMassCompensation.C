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
    starts from); on a run resumed or restarted, the acceleration and torque of the six-DoF
    state it starts from (the Laplacian's point condition holds them in the motion's own
    dictionary, the motion solvers in <time>/uniform/sixDoFRigidBodyMotionState), which are
    the last step's q with v1912's accelerationRelaxation 1; the acceleration of the force
    alone where neither is found.
\*---------------------------------------------------------------------------*/

#include "sixDoFRigidBodyMotionRestraint.H"
#include "sixDoFRigidBodyMotion.H"
#include "addToRunTimeSelectionTable.H"
#include "Time.H"
#include "IFstream.H"
#include "OSspecific.H"

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

    //- The six-DoF state of the motion's own dictionary, where it holds one (the Laplacian's
    //  point condition of a run resumed): acceleration, torque (body axes), orientation
    bool ownState_;
    vector stateAcceleration_, stateTorque_;
    tensor stateOrientation_;

    //- The acceleration a state ended its step with, in the restraint's coordinates: the
    //  linear one as it is; the angular one the inertia's (earth axes) inverse of its torque
    static FixedList<scalar, 6> stateAcceleration
    (
        const vector& a,
        const vector& torque,
        const tensor& Q,
        const tensor& inertia
    )
    {
        const vector angular = inv(inertia) & (Q & torque);
        FixedList<scalar, 6> q;
        for (direction i = 0; i < 3; ++i)
        {
            q[i] = a[i];
            q[3 + i] = angular[i];
        }
        return q;
    }

    //- The acceleration the state a run starts from ended its step with, if found
    bool startState
    (
        const sixDoFRigidBodyMotion& motion,
        const tensor& inertia,
        FixedList<scalar, 6>& q
    ) const
    {
        if (ownState_)
        {
            q = stateAcceleration(stateAcceleration_, stateTorque_, stateOrientation_, inertia);
            return true;
        }
        const Time& time = motion.time();  // read by this rank alone: no IOobject, no MPI
        const fileName file =
            time.path()/Time::timeName(time.startTime().value())/"uniform"
           /"sixDoFRigidBodyMotionState";
        if (!isFile(file))
        {
            return false;
        }
        IFstream stream(file);
        const dictionary state(stream);
        if
        (
            !state.found("acceleration") || !state.found("torque")
         || !state.found("orientation")
        )
        {
            return false;
        }
        q = stateAcceleration
        (
            state.get<vector>("acceleration"),
            state.get<vector>("torque"),
            state.get<tensor>("orientation"),
            inertia
        );
        return true;
    }

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
        stepStart_(Zero),
        ownState_(false),
        stateAcceleration_(Zero),
        stateTorque_(Zero),
        stateOrientation_(I)
    {
        read(dict);
        // the restraint's dictionary sits in the motion's "restraints"
        if (&dict.parent() != &dictionary::null && &dict.parent().parent() != &dictionary::null)
        {
            const dictionary& motionDict = dict.parent().parent();
            ownState_ =
                motionDict.found("acceleration") && motionDict.found("torque")
             && motionDict.found("orientation");
            if (ownState_)
            {
                motionDict.readEntry("acceleration", stateAcceleration_);
                motionDict.readEntry("torque", stateTorque_);
                motionDict.readEntry("orientation", stateOrientation_);
            }
        }
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
            stepStart_ = last_;
            word source("a release from rest");
            if (released)
            {
                stepStart_ = FixedList<scalar, 6>(Zero);
            }
            else if (startState(motion, inertia, stepStart_))
            {
                source = ownState_ ? "the motion's state" : "the state file";
            }
            else
            {
                source = "the force alone";
            }
            Info<< "addedMassCompensation: the acceleration before the first step from "
                << source << endl;
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
