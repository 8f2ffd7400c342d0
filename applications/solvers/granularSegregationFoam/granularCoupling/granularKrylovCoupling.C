/*---------------------------------------------------------------------------*\
    granularSegregationFoam: coupled mu(I) rheology and size segregation
    Copyright (C) 2026 The granularSegregationFoam authors
    License: GNU General Public License v3 or later (see LICENSE)
\*---------------------------------------------------------------------------*/

#include "granularKrylovCoupling.H"
#include "granularCoupling.H"
#include "fvMatrices.H"
#include "fvm.H"
#include "fvc.H"
#include "constrainHbyA.H"
#include "constrainPressure.H"
#include "SquareMatrix.H"
#include "granularInput.H"
#include "profiling.H"

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
});


// * * * * * * * * * * * * * * * Local Classes * * * * * * * * * * * * * * * //

namespace Foam
{
namespace
{

//- The patch types of a correction to field: zero where the field is
//  fixed, zero normal gradient elsewhere, constraint patches kept
template<class Type>
wordList homogeneousPatchTypes
(
    const GeometricField<Type, fvPatchField, volMesh>& field
)
{
    wordList types(field.boundaryField().size());
    forAll(types, patchi)
    {
        const fvPatchField<Type>& pf = field.boundaryField()[patchi];
        if (polyPatch::constraintType(pf.patch().type()))
        {
            types[patchi] = pf.patch().type();
        }
        else if (pf.fixesValue())
        {
            types[patchi] = "fixedValue";
        }
        else
        {
            types[patchi] = "zeroGradient";
        }
    }
    return types;
}


//- The linear part of an fvMatrix (its diagonal with the boundary's, its
//  neighbours and its coupled patches; no source), applied to a field or
//  solved for one, per component and without writing to the log
template<class Type>
class homogeneousOperator
{
    //- A copy of the matrix, whose diagonal is set per component
    fvMatrix<Type> M_;

    const scalarField diag0_;

    const lduInterfaceFieldPtrsList interfaces_;

    const dictionary controls_;

    //- Set the diagonal of component cmpt; its coupled coefficients
    void setComponent
    (
        const direction cmpt,
        FieldField<Field, scalar>& bouCoeffs,
        FieldField<Field, scalar>& intCoeffs
    )
    {
        scalarField& diag = M_.diag();
        diag = diag0_;
        forAll(M_.internalCoeffs(), patchi)
        {
            const labelUList& cells = M_.lduAddr().patchAddr(patchi);
            const Field<Type>& ic = M_.internalCoeffs()[patchi];
            forAll(cells, i)
            {
                diag[cells[i]] += component(ic[i], cmpt);
            }
        }
        bouCoeffs = M_.boundaryCoeffs().component(cmpt);
        intCoeffs = M_.internalCoeffs().component(cmpt);
    }

    //- The field whose valid components are op(cmpt, the component of x)
    //  with the matrix of that component set; the others zero
    template<class Op>
    tmp<Field<Type>> perComponent(const Field<Type>& x, const Op& op)
    {
        tmp<Field<Type>> tresult(new Field<Type>(x.size(), Zero));
        const auto valid = M_.psi().mesh().template validComponents<Type>();
        FieldField<Field, scalar> bouCoeffs, intCoeffs;
        for (direction cmpt = 0; cmpt < pTraits<Type>::nComponents; ++cmpt)
        {
            if (component(valid, cmpt) == -1)
            {
                continue;
            }
            setComponent(cmpt, bouCoeffs, intCoeffs);
            tresult.ref().replace
            (
                cmpt,
                op(cmpt, bouCoeffs, intCoeffs, x.component(cmpt))
            );
        }
        return tresult;
    }

public:

    homogeneousOperator
    (
        const fvMatrix<Type>& M,
        const GeometricField<Type, fvPatchField, volMesh>& field,
        const dictionary& controls
    )
    :
        M_(M),
        diag0_(M.diag()),
        interfaces_(field.boundaryField().scalarInterfaces()),
        controls_(controls)
    {}

    //- A psi per unit volume
    tmp<Field<Type>> apply(const Field<Type>& psi)
    {
        const scalarField& V = M_.psi().mesh().V();
        return perComponent
        (
            psi,
            [&]
            (
                const direction cmpt,
                const FieldField<Field, scalar>& bouCoeffs,
                const FieldField<Field, scalar>&,
                const tmp<scalarField>& psiCmpt
            )
            {
                solveScalarField Apsi(psi.size());
                M_.Amul(Apsi, psiCmpt, bouCoeffs, interfaces_, cmpt);
                return tmp<scalarField>::New(Apsi/V);
            }
        );
    }

    //- The psi with A psi = V rhs, from zero; adds the solver's iterations
    tmp<Field<Type>> solve(const Field<Type>& rhs, label& nIter)
    {
        const scalarField& V = M_.psi().mesh().V();
        return perComponent
        (
            rhs,
            [&]
            (
                const direction cmpt,
                const FieldField<Field, scalar>& bouCoeffs,
                const FieldField<Field, scalar>& intCoeffs,
                const tmp<scalarField>& rhsCmpt
            )
            {
                tmp<scalarField> tpsi(new scalarField(rhs.size(), Zero));
                const scalarField source(V*rhsCmpt());
                nIter += lduMatrix::solver::New
                (
                    M_.psi().name() + "Krylov",
                    M_,
                    bouCoeffs,
                    intCoeffs,
                    interfaces_,
                    controls_
                )->solve(tpsi.ref(), source, cmpt).nIterations();
                return tpsi;
            }
        );
    }
};


//- A vector of the Krylov space: a velocity and a pressure per cell
struct coupledVector
{
    vectorField u;
    scalarField p;

    coupledVector(const label n)
    :
        u(n, Zero),
        p(n, Zero)
    {}

    coupledVector(const vectorField& u0, const scalarField& p0)
    :
        u(u0),
        p(p0)
    {}
};


//- A dictionary of fvSolution's solvers with tolerance 0 and the given relTol
dictionary innerControls(const dictionary& solverDict, const scalar relTol)
{
    dictionary controls(solverDict);
    controls.set("tolerance", scalar(0));
    controls.set("relTol", relTol);
    return controls;
}


//- The solution of one frozen step: the residual, the operator, the
//  preconditioner and the Krylov vectors' inner product
class coupledStep
{
    const granularKrylovCoupling::frozenStep& s_;

    volVectorField& U_;

    volScalarField& p_;

    const fvMesh& mesh_;

    const granularKrylovCoupling::preconditioner preconditioner_;

    //- The scales of the residuals to m/s: dt/rho and the cell size
    scalarField scaleU_;

    scalarField scaleP_;

    const scalar totalV_;

    homogeneousOperator<vector> A_;

    //- The Laplacian, built at its first use: its fixedFluxPressure
    //  conditions need the gradient that residual() sets
    autoPtr<homogeneousOperator<scalar>> L_;

    const scalar innerRelTol_;

    //- A correction of p_rgh and of U with their homogeneous conditions
    volScalarField dp_;

    volVectorField dU_;

    label nPressureSolutions_;

    label nInnerIter_;

    //- The cell size h: the cube root of the volume in 3D, the square
    //  root of the area in 2D (the volume over the empty directions' span)
    static tmp<scalarField> cellSize(const fvMesh& mesh)
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

    static fvScalarMatrix pressureLaplacian
    (
        const granularKrylovCoupling::frozenStep& s,
        volScalarField& p
    )
    {
        fvScalarMatrix L(fvm::laplacian(s.rAUf, p));
        L.setReference(s.pRefCell, 0);
        return L;
    }

    //- The face gradient of the homogeneous correction t, reconstructed
    tmp<vectorField> gradient(const scalarField& t)
    {
        dp_.primitiveFieldRef() = t;
        dp_.correctBoundaryConditions();
        return tmp<vectorField>::New
        (
            s_.reconstruct(fvc::snGrad(dp_)*mesh_.magSf())().primitiveField()
        );
    }

    //- The divergence of the flux of the homogeneous correction v
    tmp<scalarField> divergence(const vectorField& v)
    {
        dU_.primitiveFieldRef() = v;
        dU_.correctBoundaryConditions();
        return tmp<scalarField>::New
        (
            fvc::div(fvc::flux(dU_))().primitiveField()
        );
    }

    //- The solution t of L t = r
    tmp<scalarField> laplacianSolve(const scalarField& r)
    {
        if (!L_)
        {
            L_.reset
            (
                new homogeneousOperator<scalar>
                (
                    pressureLaplacian(s_, p_),
                    p_,
                    innerControls(mesh_.solverDict(p_.name()), innerRelTol_)
                )
            );
        }
        ++nPressureSolutions_;
        addProfiling(laplacian, "granular::Krylov::laplacianSolve");
        return L_->solve(r, nInnerIter_);
    }


public:

    coupledStep
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

    //- Iterations of the inner U and p_rgh solutions, summed
    label nInnerIterations() const
    {
        return nInnerIter_;
    }

    label nPressureSolutions() const
    {
        return nPressureSolutions_;
    }

    //- The residual of (4.1)-(4.2) at the given U and p_rgh (set into the
    //  solver's fields), scaled to m/s: the momentum residual b - A U with
    //  the reconstructed face forces and p_rgh gradient, and minus the
    //  divergence of the corrector's flux
    coupledVector residual(const coupledVector& x)
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

        coupledVector r(x.u.size());
        r.u =
            s_.reconstruct(s_.faceForce*mesh_.magSf() - gradpf)
            ().primitiveField()
          - (s_.UEqn & U_)().primitiveField();
        r.u *= scaleU_;
        r.p = -fvc::div(phiHbyA - s_.rAUf*gradpf)().primitiveField();
        r.p *= scaleP_;
        return r;
    }

    //- The preconditioner applied to a scaled residual r
    coupledVector precondition(const coupledVector& r)
    {
        const vectorField ru(r.u/scaleU_);
        const scalarField rc(r.p/scaleP_);

        coupledVector z(ru.size());

        // The pressure from the approximate Schur complement
        const tmp<scalarField> t(laplacianSolve(rc));
        if (preconditioner_ == granularKrylovCoupling::preconditioner::BFBt)
        {
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
            z.p = -t();
        }

        // The velocity from the momentum matrix with that pressure
        addProfiling(momentum, "granular::Krylov::momentumSolve");
        z.u = A_.solve(ru - gradient(z.p), nInnerIter_);

        return z;
    }

    //- The volume-weighted inner product of two Krylov vectors
    scalar dot(const coupledVector& a, const coupledVector& b) const
    {
        const scalarField& V = mesh_.V();
        return
            gSum(V*((a.u & b.u) + a.p*b.p))/totalV_;
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
    preconditioner_(preconditioner::BFBt),
    tolerance_(1e-2),
    maxIter_(20),
    innerRelTol_(0.01),
    nIter_(0),
    relResidual_(0),
    nPressureSolutions_(0)
{
    read();
}


// * * * * * * * * * * * * * * * Member Functions  * * * * * * * * * * * * * //

void Foam::granularKrylovCoupling::read()
{
    // The Krylov dictionary is optional; present, it must be a dictionary
    const dictionary& pimpleDict = pimple_.dict();
    const dictionary dict
    (
        pimpleDict.found("Krylov", keyType::LITERAL)
      ? granularInput::subDict
        (
            pimpleDict, "Krylov", "the settings of pressureCoupling Krylov"
        )
      : pimpleDict.subOrEmptyDict("Krylov")
    );

    preconditioner_ = preconditionerNames.getOrDefault
    (
        "preconditioner", dict, preconditioner::BFBt
    );

    tolerance_ = dict.getOrDefault<scalar>("tolerance", 1e-2);
    if (!(tolerance_ > 0 && tolerance_ < 1))
    {
        granularInput::invalid(dict, "tolerance", tolerance_, "0 < tolerance < 1");
    }

    maxIter_ = dict.getOrDefault<label>("maxIter", 20);
    if (maxIter_ < 1)
    {
        granularInput::invalid(dict, "maxIter", maxIter_, ">= 1");
    }

    innerRelTol_ = dict.getOrDefault<scalar>("innerRelTol", 0.01);
    if (!(innerRelTol_ > 0 && innerRelTol_ < 1))
    {
        granularInput::invalid
        (
            dict, "innerRelTol", innerRelTol_, "0 < innerRelTol < 1"
        );
    }
}


void Foam::granularKrylovCoupling::solve
(
    const frozenStep& step,
    volVectorField& U,
    volScalarField& p_rgh
)
{
    coupledStep cs(step, U, p_rgh, preconditioner_, innerRelTol_);

    const coupledVector x0(U.primitiveField(), p_rgh.primitiveField());
    const coupledVector r0(cs.residual(x0));
    const scalar beta = Foam::sqrt(cs.dot(r0, r0));

    // The iterations end once the residual, in m/s, is below tolerance
    // times the RMS speed (or times the initial residual in a fluid at
    // rest): relative to the initial residual instead, the air's
    // continuity residual after the phases moved, which the first
    // iteration removes, would set the target
    const coupledVector u0(x0.u, scalarField(x0.p.size(), Zero));
    const scalar speed = Foam::sqrt(cs.dot(u0, u0));
    const scalar target = tolerance_*(speed > 0 ? speed : beta);

    // FGMRES with right preconditioning, Givens rotations and modified
    // Gram-Schmidt (Saad 1993)
    PtrList<coupledVector> V(maxIter_ + 1);
    PtrList<coupledVector> Z(maxIter_);
    SquareMatrix<scalar> H(maxIter_ + 1, Zero);
    // The Hessenberg matrix before the rotations, for the debug log
    SquareMatrix<scalar> H0(debug ? maxIter_ + 1 : 0, Zero);
    scalarList g(maxIter_ + 1, Zero);
    scalarList cs1(maxIter_, Zero);
    scalarList sn1(maxIter_, Zero);

    label k = 0;
    scalar res = beta;

    if (beta > 0)
    {
        V.set(0, new coupledVector(r0.u/beta, r0.p/beta));
        g[0] = beta;

        while (k < maxIter_ && res > target)
        {
            Z.set(k, new coupledVector(cs.precondition(V[k])));

            // w = K z = r(x0) - r(x0 + z): the residual is affine
            coupledVector w
            (
                cs.residual
                (
                    coupledVector(x0.u + Z[k].u, x0.p + Z[k].p)
                )
            );
            w.u = r0.u - w.u;
            w.p = r0.p - w.p;

            for (label i = 0; i <= k; ++i)
            {
                H(i, k) = cs.dot(w, V[i]);
                w.u -= H(i, k)*V[i].u;
                w.p -= H(i, k)*V[i].p;
            }
            H(k + 1, k) = Foam::sqrt(cs.dot(w, w));
            if (debug)
            {
                for (label i = 0; i <= k + 1; ++i)
                {
                    H0(i, k) = H(i, k);
                }
            }
            V.set
            (
                k + 1,
                new coupledVector
                (
                    w.u/max(H(k + 1, k), VSMALL),
                    w.p/max(H(k + 1, k), VSMALL)
                )
            );

            // The earlier rotations on the new column, then its own
            for (label i = 0; i < k; ++i)
            {
                const scalar h0 = H(i, k);
                H(i, k) = cs1[i]*h0 + sn1[i]*H(i + 1, k);
                H(i + 1, k) = -sn1[i]*h0 + cs1[i]*H(i + 1, k);
            }
            const scalar d = Foam::sqrt(sqr(H(k, k)) + sqr(H(k + 1, k)));
            cs1[k] = H(k, k)/max(d, VSMALL);
            sn1[k] = H(k + 1, k)/max(d, VSMALL);
            H(k, k) = d;
            H(k + 1, k) = 0;
            g[k + 1] = -sn1[k]*g[k];
            g[k] = cs1[k]*g[k];

            res = mag(g[k + 1]);
            ++k;
        }
    }

    // x = x0 + Z y, H y = g on the first k rows
    scalarList y(k, Zero);
    for (label i = k - 1; i >= 0; --i)
    {
        scalar sum = g[i];
        for (label j = i + 1; j < k; ++j)
        {
            sum -= H(i, j)*y[j];
        }
        y[i] = sum/H(i, i);
    }

    vectorField u(x0.u);
    scalarField p(x0.p);
    for (label i = 0; i < k; ++i)
    {
        u += y[i]*Z[i].u;
        p += y[i]*Z[i].p;
    }
    U.primitiveFieldRef() = u;
    U.correctBoundaryConditions();
    p_rgh.primitiveFieldRef() = p;
    p_rgh.correctBoundaryConditions();


    if (debug && k > 0)
    {
        Info<< "Krylov coupling: Hessenberg matrix (" << k + 1 << " x "
            << k << ", rows)" << nl;
        for (label i = 0; i <= k; ++i)
        {
            Info<< "   ";
            for (label j = 0; j < k; ++j)
            {
                Info<< ' ' << H0(i, j);
            }
            Info<< nl;
        }
        Info<< endl;
    }

    p_rgh_.reset(new volScalarField("p_rghKrylov", p_rgh));

    nIter_ = k;
    relResidual_ = res/(speed > 0 ? speed : max(beta, VSMALL));
    nPressureSolutions_ = cs.nPressureSolutions();

    Info<< "Krylov coupling: " << preconditionerNames[preconditioner_]
        << ", " << nIter_ << " iterations (" << cs.nInnerIterations()
        << " of the inner solvers), residual " << beta << " -> "
        << res << " m/s, " << relResidual_ << " of the "
        << (speed > 0 ? "RMS speed" : "initial residual");
    if (res > target)
    {
        Info<< ": not converged to tolerance " << tolerance_
            << " within maxIter " << maxIter_;
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
