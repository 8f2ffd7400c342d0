/*---------------------------------------------------------------------------*\
    granularSegregationFoam: coupled mu(I) rheology and size segregation
    Copyright (C) 2026 The granularSegregationFoam authors
    License: GNU General Public License v3 or later (see LICENSE)
\*---------------------------------------------------------------------------*/

#include "granularKrylovCoupling.H"
#include "KrylovStep.H"
#include "SquareMatrix.H"
#include "granularInput.H"

// * * * * * * * * * * * * * * * Static Data * * * * * * * * * * * * * * * * //

namespace Foam
{
    defineTypeNameAndDebug(granularKrylovCoupling, 0);
}


const Foam::Enum<Foam::granularKrylovCoupling::preconditioner>
Foam::granularKrylovCoupling::preconditionerNames
({
    { preconditioner::PISO, "PISO" },
    { preconditioner::BFBt, "BFBt" },
    { preconditioner::CahouetChabard, "CahouetChabard" },
});


// * * * * * * * * * * * * * * * Local Classes * * * * * * * * * * * * * * * //

namespace Foam
{
namespace
{

//- FGMRES with right preconditioning, Givens rotations and modified
//  Gram-Schmidt (Saad 1993): the Krylov basis V, the preconditioned
//  vectors Z, the rotated Hessenberg matrix and its right-hand side g
class FGMRES
{
    PtrList<KrylovVector> V_;

    PtrList<KrylovVector> Z_;

    SquareMatrix<scalar> H_;

    //- The Hessenberg matrix before the rotations, for the debug log
    SquareMatrix<scalar> H0_;

    scalarList g_;

    scalarList c_;

    scalarList s_;

    label k_;

    //- The earlier rotations on column k, then its own; the new g
    void rotate(const label k)
    {
        for (label i = 0; i < k; ++i)
        {
            const scalar h0 = H_(i, k);
            H_(i, k) = c_[i]*h0 + s_[i]*H_(i + 1, k);
            H_(i + 1, k) = -s_[i]*h0 + c_[i]*H_(i + 1, k);
        }
        const scalar d = Foam::sqrt(sqr(H_(k, k)) + sqr(H_(k + 1, k)));
        c_[k] = H_(k, k)/max(d, VSMALL);
        s_[k] = H_(k + 1, k)/max(d, VSMALL);
        H_(k, k) = d;
        H_(k + 1, k) = 0;
        g_[k + 1] = -s_[k]*g_[k];
        g_[k] = c_[k]*g_[k];
    }

public:

    //- From the initial residual r0 of norm beta > 0
    FGMRES
    (
        const label maxIter,
        const KrylovVector& r0,
        const scalar beta,
        const bool keepHessenberg
    )
    :
        V_(maxIter + 1),
        Z_(maxIter),
        H_(maxIter + 1, Zero),
        H0_(keepHessenberg ? maxIter + 1 : 0, Zero),
        g_(maxIter + 1, Zero),
        c_(maxIter, Zero),
        s_(maxIter, Zero),
        k_(0)
    {
        V_.set(0, new KrylovVector(r0.u/beta, r0.p/beta));
        g_[0] = beta;
    }

    //- The basis vector the next iteration preconditions
    const KrylovVector& basis() const
    {
        return V_[k_];
    }

    //- Adds the preconditioned basis vector z and its image w = K z;
    //  returns the norm of the residual reached
    scalar add(KrylovVector* z, KrylovVector w, const KrylovStep& step)
    {
        const label k = k_;
        Z_.set(k, z);
        for (label i = 0; i <= k; ++i)
        {
            H_(i, k) = step.dot(w, V_[i]);
            w.u -= H_(i, k)*V_[i].u;
            w.p -= H_(i, k)*V_[i].p;
        }
        H_(k + 1, k) = Foam::sqrt(step.dot(w, w));
        if (H0_.m())
        {
            for (label i = 0; i <= k + 1; ++i)
            {
                H0_(i, k) = H_(i, k);
            }
        }
        V_.set
        (
            k + 1,
            new KrylovVector
            (
                w.u/max(H_(k + 1, k), VSMALL),
                w.p/max(H_(k + 1, k), VSMALL)
            )
        );
        rotate(k);
        ++k_;
        return mag(g_[k + 1]);
    }

    label nIter() const
    {
        return k_;
    }

    //- x0 + Z y, with H y = g on the first k rows
    void correct(vectorField& u, scalarField& p) const
    {
        const label k = k_;
        scalarList y(k, Zero);
        for (label i = k - 1; i >= 0; --i)
        {
            scalar sum = g_[i];
            for (label j = i + 1; j < k; ++j)
            {
                sum -= H_(i, j)*y[j];
            }
            y[i] = sum/H_(i, i);
        }
        for (label i = 0; i < k; ++i)
        {
            u += y[i]*Z_[i].u;
            p += y[i]*Z_[i].p;
        }
    }

    //- The Hessenberg matrix before the rotations, by rows
    void printHessenberg() const
    {
        Info<< "Krylov coupling: Hessenberg matrix (" << k_ + 1 << " x "
            << k_ << ", rows)" << nl;
        for (label i = 0; i <= k_; ++i)
        {
            Info<< "   ";
            for (label j = 0; j < k_; ++j)
            {
                Info<< ' ' << H0_(i, j);
            }
            Info<< nl;
        }
        Info<< endl;
    }
};

} // End anonymous namespace
} // End namespace Foam


// * * * * * * * * * * * * * * * * Constructors  * * * * * * * * * * * * * * //

Foam::granularKrylovCoupling::granularKrylovCoupling
(
    const pimpleControl& pimple
)
:
    pimple_(pimple),
    settings_(readSettings(dictionary::null)),
    finalSettings_(settings_),
    nIter_(0),
    relResidual_(0),
    nPressureSolutions_(0)
{
    read();
}


// * * * * * * * * * * * * * * * Member Functions  * * * * * * * * * * * * * //

Foam::granularKrylovCoupling::settings
Foam::granularKrylovCoupling::readSettings(const dictionary& dict)
{
    settings s;

    s.schur = granularInput::readEnum
    (
        dict, "preconditioner",
        preconditionerNames, preconditioner::CahouetChabard
    );

    s.tolerance = dict.getOrDefault<scalar>("tolerance", 1e-2);
    if (!(s.tolerance > 0 && s.tolerance < 1))
    {
        granularInput::invalid
        (
            dict, "tolerance", s.tolerance, "0 < tolerance < 1"
        );
    }

    s.maxIter = dict.getOrDefault<label>("maxIter", 20);
    if (s.maxIter < 1)
    {
        granularInput::invalid(dict, "maxIter", s.maxIter, ">= 1");
    }

    s.innerRelTol = dict.getOrDefault<scalar>("innerRelTol", 0.01);
    if (!(s.innerRelTol > 0 && s.innerRelTol < 1))
    {
        granularInput::invalid
        (
            dict, "innerRelTol", s.innerRelTol, "0 < innerRelTol < 1"
        );
    }

    return s;
}


void Foam::granularKrylovCoupling::read()
{
    // The Krylov dictionary is optional; present, it must be a dictionary
    const dictionary& pimpleDict = pimple_.dict();
    settings_ = readSettings
    (
        pimpleDict.found("Krylov", keyType::LITERAL)
      ? granularInput::subDict
        (
            pimpleDict, "Krylov", "the settings of pressureCoupling Krylov"
        )
      : pimpleDict.subOrEmptyDict("Krylov")
    );

    // KrylovFinal, for the final outer iteration, likewise; absent, Krylov
    finalSettings_ =
    (
        pimpleDict.found("KrylovFinal", keyType::LITERAL)
      ? readSettings
        (
            granularInput::subDict
            (
                pimpleDict, "KrylovFinal",
                "the Krylov settings of the final outer iteration"
            )
        )
      : settings_
    );
}



void Foam::granularKrylovCoupling::solve
(
    const frozenStep& step,
    volVectorField& U,
    volScalarField& p_rgh,
    const bool lastPass
)
{
    const settings& set =
        pimple_.finalIter() && lastPass ? finalSettings_ : settings_;

    KrylovStep ks(step, U, p_rgh, set.schur, set.innerRelTol);

    const KrylovVector x0(U.primitiveField(), p_rgh.primitiveField());
    const KrylovVector r0(ks.residual(x0));
    const scalar beta = Foam::sqrt(ks.dot(r0, r0));

    // The iterations end once the residual, in m/s, is below tolerance
    // times the RMS speed (or times the initial residual in a fluid at
    // rest): relative to the initial residual instead, the air's
    // continuity residual after the phases moved, which the first
    // iteration removes, would set the target
    const KrylovVector u0(x0.u, scalarField(x0.p.size(), Zero));
    const scalar speed = Foam::sqrt(ks.dot(u0, u0));
    const scalar target = set.tolerance*(speed > 0 ? speed : beta);

    vectorField u(x0.u);
    scalarField p(x0.p);
    scalar res = beta;
    nIter_ = 0;
    if (beta > 0)
    {
        FGMRES fgmres(set.maxIter, r0, beta, debug);
        while (fgmres.nIter() < set.maxIter && res > target)
        {
            autoPtr<KrylovVector> z
            (
                new KrylovVector(ks.precondition(fgmres.basis()))
            );

            // w = K z = r(x0) - r(x0 + z): the residual is affine
            KrylovVector w
            (
                ks.residual(KrylovVector(x0.u + z->u, x0.p + z->p))
            );
            w.u = r0.u - w.u;
            w.p = r0.p - w.p;

            res = fgmres.add(z.release(), w, ks);
        }
        fgmres.correct(u, p);
        nIter_ = fgmres.nIter();
        if (debug && nIter_ > 0)
        {
            fgmres.printHessenberg();
        }
    }
    U.primitiveFieldRef() = u;
    U.correctBoundaryConditions();
    p_rgh.primitiveFieldRef() = p;
    p_rgh.correctBoundaryConditions();

    p_rgh_.reset(new volScalarField("p_rghKrylov", p_rgh));

    relResidual_ = res/(speed > 0 ? speed : max(beta, VSMALL));
    nPressureSolutions_ = ks.nPressureSolutions();

    Info<< "Krylov coupling: " << preconditionerNames[set.schur]
        << ", " << nIter_ << " iterations (" << ks.nInnerIterations()
        << " of the inner solvers), residual " << beta << " -> "
        << res << " m/s, " << relResidual_ << " of the "
        << (speed > 0 ? "RMS speed" : "initial residual");
    if (res > target)
    {
        Info<< ": not converged to tolerance " << set.tolerance
            << " within maxIter " << set.maxIter;
    }
    Info<< endl;
}



void Foam::granularKrylovCoupling::restorePressure
(
    volScalarField& p_rgh,
    volScalarField& p,
    const volScalarField& rho,
    const volScalarField& gh
) const
{
    p_rgh = p_rgh_();
    p == p_rgh + rho*gh;
}


// ************************************************************************* //
