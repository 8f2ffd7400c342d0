/*---------------------------------------------------------------------------*\
    granularSegregationFoam: coupled mu(I) rheology and size segregation
    Copyright (C) 2026 The granularSegregationFoam authors
    License: GNU General Public License v3 or later (see LICENSE)
\*---------------------------------------------------------------------------*/

#include "KrylovStep.H"
#include "granularCoupling.H"
#include "fvm.H"
#include "fvc.H"
#include "constrainHbyA.H"
#include "constrainPressure.H"
#include "profiling.H"
#include "extrapolatedCalculatedFvPatchFields.H"

// * * * * * * * * * * * * * * * Local Functions * * * * * * * * * * * * * * //

namespace Foam
{
namespace
{

//- A dictionary of fvSolution's solvers with tolerance 0 and the given relTol
dictionary innerControls(const dictionary& solverDict, const scalar relTol)
{
    dictionary controls(solverDict);
    controls.set("tolerance", scalar(0));
    controls.set("relTol", relTol);
    return controls;
}

} // End anonymous namespace
} // End namespace Foam


// * * * * * * * * * * * * * Private Member Functions  * * * * * * * * * * * //

Foam::tmp<Foam::scalarField> Foam::KrylovStep::cellSize(const fvMesh& mesh)
{
    const Vector<label>& solD = mesh.solutionD();
    const vector span(mesh.bounds().span());
    scalar thickness = 1;
    for (direction d = 0; d < vector::nComponents; ++d)
    {
        if (solD[d] == -1)
        {
            thickness *= span[d];
        }
    }
    return pow
    (
        mesh.V().field()/thickness,
        1.0/scalar(mesh.nSolutionD())
    );
}


Foam::autoPtr<Foam::homogeneousOperator<Foam::scalar>>
Foam::KrylovStep::laplacian(const surfaceScalarField& coefficient)
{
    fvScalarMatrix L(fvm::laplacian(coefficient, p_));
    L.setReference(s_.pRefCell, 0);
    return autoPtr<homogeneousOperator<scalar>>::New
    (
        L,
        p_,
        innerControls(mesh_.solverDict(p_.name()), innerRelTol_)
    );
}


Foam::tmp<Foam::scalarField> Foam::KrylovStep::solve
(
    homogeneousOperator<scalar>& L,
    const scalarField& r
)
{
    ++nPressureSolutions_;
    addProfiling(laplacian, "granular::Krylov::laplacianSolve");
    return L.solve(r, nInnerIter_);
}


Foam::tmp<Foam::vectorField> Foam::KrylovStep::gradient(const scalarField& t)
{
    dp_.primitiveFieldRef() = t;
    dp_.correctBoundaryConditions();
    return tmp<vectorField>::New
    (
        s_.reconstruct(fvc::snGrad(dp_)*mesh_.magSf())().primitiveField()
    );
}


Foam::tmp<Foam::scalarField> Foam::KrylovStep::divergence
(
    const vectorField& v
)
{
    dU_.primitiveFieldRef() = v;
    dU_.correctBoundaryConditions();
    return tmp<scalarField>::New
    (
        fvc::div(fvc::flux(dU_))().primitiveField()
    );
}


Foam::tmp<Foam::scalarField> Foam::KrylovStep::laplacianSolve
(
    const scalarField& r
)
{
    if (!L_)
    {
        L_ = laplacian(s_.rAUf);
    }
    return solve(*L_, r);
}


Foam::scalar Foam::KrylovStep::ddtCoefficient() const
{
    const ITstream& ddt = mesh_.ddtScheme("ddt(rho,U)");
    const word scheme
    (
        ddt.size() && ddt[0].isWord() ? ddt[0].wordToken() : word()
    );
    if (scheme == "Euler")
    {
        return 1;
    }
    if (scheme == "backward")
    {
        const Time& time = mesh_.time();
        const scalar dt = time.deltaTValue();
        return time.timeIndex() < 2 ? 1 : 1 + dt/(dt + time.deltaT0Value());
    }

    FatalIOErrorInFunction(mesh_.schemesDict())
        << "ddtSchemes: the Krylov coupling's preconditioner "
        << "CahouetChabard needs ddt(rho,U) Euler or backward, not ";
    if (scheme.size())
    {
        FatalIOError<< scheme;
    }
    else
    {
        FatalIOError<< ddt;
    }
    FatalIOError<< exit(FatalIOError);
    return 1;
}


const Foam::volScalarField& Foam::KrylovStep::eta() const
{
    // The mixture's viscosity (4.7b)
    return mesh_.lookupObject<volScalarField>("granularMixture:eta");
}


Foam::tmp<Foam::surfaceScalarField>
Foam::KrylovStep::inertialCoefficient() const
{
    // The diagonal of the stress's Laplacian, its orthogonal part
    const scalarField viscous
    (
        fvc::surfaceSum
        (
            fvc::interpolate(eta())*mesh_.magSf()*mesh_.nonOrthDeltaCoeffs()
        )().primitiveField()/mesh_.V()
    );

    volScalarField A
    (
        IOobject("AinertiaKrylov", mesh_.time().timeName(), mesh_),
        mesh_,
        dimensionedScalar(dimDensity/dimTime, Zero),
        extrapolatedCalculatedFvPatchScalarField::typeName
    );
    A.primitiveFieldRef() = max
    (
        1.0/s_.rAU.primitiveField() - viscous,
        // at least the time derivative's rho/dt
        ddtCoefficient()*s_.rho.primitiveField()/mesh_.time().deltaTValue()
    );
    A.correctBoundaryConditions();

    return tmp<surfaceScalarField>::New
    (
        "rAinertiaf",
        fvc::interpolate(1.0/A)
    );
}


Foam::tmp<Foam::scalarField> Foam::KrylovStep::CahouetChabard
(
    const scalarField& r
)
{
    if (!Linertia_)
    {
        Linertia_ = laplacian(inertialCoefficient());
    }
    return solve(*Linertia_, r) - eta().primitiveField()*r;
}


// * * * * * * * * * * * * * * * * Constructors  * * * * * * * * * * * * * * //

Foam::KrylovStep::KrylovStep
(
    const granularKrylovCoupling::frozenStep& s,
    volVectorField& U,
    volScalarField& p_rgh,
    const granularKrylovCoupling::preconditioner precon,
    const scalar innerRelTol
)
:
    s_(s),
    U_(U),
    p_(p_rgh),
    mesh_(U.mesh()),
    preconditioner_(precon),
    scaleU_(mesh_.time().deltaTValue()/s.rho.primitiveField()),
    scaleP_
    (
        cellSize(mesh_)*scaleU_/s.rAU.primitiveField()
    ),
    totalV_(gSum(mesh_.V())),
    A_
    (
        s.UEqn,
        U,
        innerControls(mesh_.solverDict(U.name()), innerRelTol)
    ),
    L_(),
    Linertia_(),
    innerRelTol_(innerRelTol),
    dp_
    (
        IOobject("dp_rghKrylov", mesh_.time().timeName(), mesh_),
        mesh_,
        dimensionedScalar(p_rgh.dimensions(), Zero),
        homogeneousPatchTypes(p_rgh)
    ),
    dU_
    (
        IOobject("dUKrylov", mesh_.time().timeName(), mesh_),
        mesh_,
        dimensionedVector(U.dimensions(), Zero),
        homogeneousPatchTypes(U)
    ),
    nPressureSolutions_(0),
    nInnerIter_(0)
{}


// * * * * * * * * * * * * * * * Member Functions  * * * * * * * * * * * * * //

Foam::KrylovVector Foam::KrylovStep::residual(const KrylovVector& x)
{
    addProfiling(residual, "granular::Krylov::residual");
    U_.primitiveFieldRef() = x.u;
    U_.correctBoundaryConditions();
    p_.primitiveFieldRef() = x.p;

    volVectorField HbyA(constrainHbyA(s_.rAU*s_.UEqn.H(), U_, p_));
    surfaceScalarField phiHbyA
    (
        granularCoupling::fluxHbyA(HbyA, s_.phiDdtCorr, U_, p_, s_.MRF)
      + s_.phig
    );
    constrainPressure(p_, U_, phiHbyA, s_.rAUf, s_.MRF);
    p_.correctBoundaryConditions();

    const surfaceScalarField gradpf(fvc::snGrad(p_)*mesh_.magSf());

    KrylovVector r(x.u.size());
    r.u =
        s_.reconstruct(s_.faceForce*mesh_.magSf() - gradpf)
        ().primitiveField()
      - (s_.UEqn & U_)().primitiveField();
    r.u *= scaleU_;
    r.p = -fvc::div(phiHbyA - s_.rAUf*gradpf)().primitiveField();
    r.p *= scaleP_;
    return r;
}


Foam::KrylovVector Foam::KrylovStep::precondition(const KrylovVector& r)
{
    const vectorField ru(r.u/scaleU_);
    const scalarField rc(r.p/scaleP_);

    KrylovVector z(ru.size());

    // The pressure from the approximate Schur complement
    typedef granularKrylovCoupling::preconditioner schur;
    if (preconditioner_ == schur::CahouetChabard)
    {
        // S^-1 = (D (dt/rho) G)^-1 - eta: the inertial and viscous limits
        z.p = -CahouetChabard(rc);
    }
    else if (preconditioner_ == schur::BFBt)
    {
        const tmp<scalarField> t(laplacianSolve(rc));
        // L^-1 (D C^-1 A C^-1 G + L - D C^-1 G) L^-1 rc
        const vectorField CG(s_.rAU.primitiveField()*gradient(t()));
        const vectorField CNCG
        (
            s_.rAU.primitiveField()*A_.apply(CG) - CG
        );
        z.p = -laplacianSolve(rc + divergence(CNCG));
    }
    else
    {
        z.p = -laplacianSolve(rc);
    }

    // The velocity from the momentum matrix with that pressure
    addProfiling(momentum, "granular::Krylov::momentumSolve");
    z.u = A_.solve(ru - gradient(z.p), nInnerIter_);

    return z;
}


Foam::scalar Foam::KrylovStep::dot
(
    const KrylovVector& a,
    const KrylovVector& b
) const
{
    const scalarField& V = mesh_.V();
    return gSum(V*((a.u & b.u) + a.p*b.p))/totalV_;
}


// ************************************************************************* //
