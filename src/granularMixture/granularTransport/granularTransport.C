/*---------------------------------------------------------------------------*\
    granularSegregationFoam: coupled mu(I) rheology and size segregation
    Copyright (C) 2026 The granularSegregationFoam authors
    License: GNU General Public License v3 or later (see LICENSE)
\*---------------------------------------------------------------------------*/

#include "granularTransport.H"
#include "granularPhases.H"
#include "granularPairFluxes.H"
#include "granularAir.H"
#include "granularGravity.H"
#include "granularRheology.H"
#include "granularInput.H"
#include "MULES.H"
#include "subCycle.H"
#include "upwind.H"
#include "fvcFlux.H"
#include "fvcSurfaceIntegrate.H"

// * * * * * * * * * * * * Private Member Functions  * * * * * * * * * * * * //

Foam::tmp<Foam::scalarField> Foam::granularTransport::boundsExcess
(
    const volScalarField& alpha,
    const surfaceScalarField& alphaPhi
) const
{
    // The update of MULES::explicitSolve, without changing the field
    scalarField psi(alpha.oldTime().primitiveField());
    if (mesh_.moving())
    {
        psi *= mesh_.Vsc0()().field()/mesh_.Vsc()().field();
    }
    psi -= mesh_.time().deltaTValue()
       *fvc::surfaceIntegrate(alphaPhi)().primitiveField();

    return max(max(-psi, psi - 1), scalar(0));
}


bool Foam::granularTransport::outOfBounds
(
    const PtrList<surfaceScalarField>& corrections,
    const PtrList<surfaceScalarField>& upwindPhis,
    const PtrList<scalarField>& upwindExcess,
    const scalar tol
) const
{
    bool out = false;
    forAll(phases_.alphas(), i)
    {
        const scalarField excess
        (
            boundsExcess(phases_[i], corrections[i] + upwindPhis[i])
          - upwindExcess[i]
        );
        out = out || max(excess) > tol;
    }
    return returnReduce(out, orOp<bool>());
}


void Foam::granularTransport::fluxes
(
    PtrList<surfaceScalarField>& alphaPhis,
    PtrList<surfaceScalarField>& relPhis
)
{
    const PtrList<volScalarField>& alphas = phases_.alphas();
    const word alphaScheme("div(phi,alpha)");
    forAll(alphas, i)
    {
        alphaPhis.set
        (
            i,
            new surfaceScalarField
            (
                "phiAlpha." + alphas[i].name(),
                fvc::flux(phi_, alphas[i], alphaScheme)
            )
        );
    }

    // The pairwise fluxes are added to alphaPhis pair by pair, the sums
    // kept apart for the check of (2.12): the chute's outflow at the
    // implicit stress's large steps is sensitive to the order of the sums
    forAll(alphas, i)
    {
        relPhis.set
        (
            i,
            new surfaceScalarField("relPhi." + alphas[i].name(), 0*alphaPhis[i])
        );
    }

    List<labelPair> pairs;
    PtrList<surfaceScalarField> phirs;
    pairFluxes_.relativeFluxes
    (
        alphas, gravity_.unit(), air_, phi_, pairs, phirs
    );
    segregationRate_ =
        pairFluxes_.add(alphas, pairs, phirs, alphaPhis, &relPhis);
}


void Foam::granularTransport::limit
(
    PtrList<surfaceScalarField>& alphaPhis,
    const PtrList<surfaceScalarField>& upwindPhis
) const
{
    PtrList<volScalarField>& alphas = phases_.alphas();

    // Bound each phase, then make the corrections sum to zero.  limitSum
    // scales corrections of one sign only, which can undo a phase's bound
    // where several phases meet (seen on moving meshes): while the update
    // would leave [0, 1] by more than 1e-12 beyond the upwind update, the
    // pair is repeated, each pass shrinking the corrections towards the
    // bounded upwind fluxes.  One pass, multiphaseInterFoam's, is the rule.
    // The upwind update itself leaves [0, 1] by the continuity error of
    // phi (about 1e-9 in the chute, within the pressure tolerance): no
    // limiting can remove that part, and the passes would repeat in vain.
    const dictionary& dict = mesh_.solverDict("alpha");
    const label nPasses = dict.getOrDefault<label>("nLimitSumPasses", 10);
    if (nPasses < 1)
    {
        granularInput::invalid(dict, "nLimitSumPasses", nPasses, ">= 1");
    }

    PtrList<scalarField> upwindExcess(alphas.size());
    forAll(alphas, i)
    {
        upwindExcess.set(i, boundsExcess(alphas[i], upwindPhis[i]));
    }
    for (label pass = 0; pass < nPasses; ++pass)
    {
        forAll(alphas, i)
        {
            if (pass > 0)
            {
                alphaPhis[i] += upwindPhis[i];
            }
            MULES::limit
            (
                1.0/mesh_.time().deltaTValue(),
                geometricOneField(),
                alphas[i],
                phi_,
                alphaPhis[i],
                zeroField(),
                zeroField(),
                oneField(),
                zeroField(),
                true
            );
        }
        MULES::limitSum(alphaPhis);

        if (!outOfBounds(alphaPhis, upwindPhis, upwindExcess, 1e-12))
        {
            break;
        }
    }
}


void Foam::granularTransport::update
(
    PtrList<surfaceScalarField>& alphaPhis,
    const PtrList<surfaceScalarField>& upwindPhis
)
{
    PtrList<volScalarField>& alphas = phases_.alphas();
    const dimensionedScalar rhoGrains(rheology_.rhoGrains());
    rhoPhi_ = dimensionedScalar(rhoPhi_.dimensions(), Zero);

    scalarField sumAlpha(mesh_.nCells(), Zero);
    forAll(alphas, i)
    {
        volScalarField& alpha = alphas[i];
        surfaceScalarField& alphaPhi = alphaPhis[i];
        alphaPhi += upwindPhis[i];

        MULES::explicitSolve(geometricOneField(), alpha, alphaPhi);

        rhoPhi_ += alphaPhi*(i == 0 ? air_.rho() : rhoGrains);
        phases_.alphaPhis()[i] = alphaPhi;
        sumAlpha += alpha.primitiveField();
    }

    // Remove the round-off drift of the sum, as multiphaseInterFoam does
    const scalarField sumCorr(1.0 - sumAlpha);
    for (volScalarField& alpha : alphas)
    {
        alpha.primitiveFieldRef() += alpha.primitiveField()*sumCorr;
        alpha.correctBoundaryConditions();
    }
}


void Foam::granularTransport::step()
{
    const label nPhases = phases_.size();

    PtrList<surfaceScalarField> alphaPhis(nPhases);
    PtrList<surfaceScalarField> relPhis(nPhases);
    fluxes(alphaPhis, relPhis);

    PtrList<surfaceScalarField> upwindPhis(nPhases);
    forAll(upwindPhis, i)
    {
        upwindPhis.set
        (
            i,
            new surfaceScalarField
            (
                upwind<scalar>(mesh_, phi_).flux(phases_[i])
            )
        );
    }
    limit(alphaPhis, upwindPhis);

    pairwiseFluxSum_.value() = max
    (
        pairwiseFluxSum_.value(), granularPairFluxes::fluxSum(relPhis)
    );
    limitedFluxSum_.value() = max
    (
        limitedFluxSum_.value(), granularPairFluxes::fluxSum(alphaPhis)
    );

    update(alphaPhis, upwindPhis);
}


// * * * * * * * * * * * * * * * * Constructors  * * * * * * * * * * * * * * //

Foam::granularTransport::granularTransport
(
    const surfaceScalarField& phi,
    granularPhases& phases,
    const granularPairFluxes& pairFluxes,
    const granularAir& air,
    const granularGravity& gravity,
    const granularRheology& rheology
)
:
    mesh_(phi.mesh()),
    phi_(phi),
    phases_(phases),
    pairFluxes_(pairFluxes),
    air_(air),
    gravity_(gravity),
    rheology_(rheology),
    rhoPhi_
    (
        IOobject
        (
            "rhoPhi",
            mesh_.time().timeName(),
            mesh_,
            IOobject::NO_READ,
            IOobject::NO_WRITE
        ),
        mesh_,
        dimensionedScalar(dimMass/dimTime, Zero)
    ),
    segregationRate_(mesh_.nCells(), Zero),
    pairwiseFluxSum_
    (
        IOobject
        (
            "pairwiseFluxSum",
            mesh_.time().constant(),
            mesh_,
            IOobject::NO_READ,
            IOobject::NO_WRITE
        ),
        dimensionedScalar(dimless, Zero)
    ),
    limitedFluxSum_
    (
        IOobject
        (
            "limitedFluxSum",
            mesh_.time().constant(),
            mesh_,
            IOobject::NO_READ,
            IOobject::NO_WRITE
        ),
        dimensionedScalar(dimless, Zero)
    )
{}


// * * * * * * * * * * * * * * * Member Functions  * * * * * * * * * * * * * //

void Foam::granularTransport::updateSegregationRate()
{
    List<labelPair> pairs;
    PtrList<surfaceScalarField> phirs;
    pairFluxes_.relativeFluxes
    (
        phases_.alphas(), gravity_.unit(), air_, phi_, pairs, phirs
    );
    segregationRate_ =
        pairFluxes_.segregationRate(phases_.alphas(), pairs, phirs);
}


Foam::label Foam::granularTransport::maxSubCycles() const
{
    const dictionary& dict = mesh_.solverDict("alpha");
    const label nMax = dict.getOrDefault<label>("maxAlphaSubCycles", 0);
    if (dict.found("maxAlphaSubCycles") && nMax < 1)
    {
        granularInput::invalid(dict, "maxAlphaSubCycles", nMax, ">= 1");
    }
    if (nMax && dict.getOrDefault<label>("nAlphaSubCycles", 1) != 1)
    {
        FatalIOErrorInFunction(dict)
            << "Invalid keywords in dictionary " << dict.name()
            << ": nAlphaSubCycles = " << dict.get<label>("nAlphaSubCycles")
            << " with maxAlphaSubCycles = " << nMax << ": give one of them"
            << " (a fixed count, or the largest adaptive count)" << nl
            << exit(FatalIOError);
    }
    return nMax;
}


Foam::label Foam::granularTransport::nSubCycles(const scalar transportCo) const
{
    const dictionary& dict = mesh_.solverDict("alpha");

    const label nMax = maxSubCycles();
    if (nMax)
    {
        // As many as keep each sub-cycle's transport part within maxAlphaCo
        const scalar maxAlphaCo =
            mesh_.time().controlDict().get<scalar>("maxAlphaCo");
        return min
        (
            nMax,
            max(label(1), label(std::ceil(transportCo/maxAlphaCo - 1e-6)))
        );
    }

    const label nSub = dict.getOrDefault<label>("nAlphaSubCycles", 1);
    if (nSub < 1)
    {
        granularInput::invalid(dict, "nAlphaSubCycles", nSub, ">= 1");
    }
    return nSub;
}


void Foam::granularTransport::solve(const label nSub)
{
    pairwiseFluxSum_.value() = 0;
    limitedFluxSum_.value() = 0;
    if (nSub <= 1)
    {
        step();
        return;
    }

    const Time& runTime = mesh_.time();
    PtrList<surfaceScalarField>& alphaPhis = phases_.alphaPhis();

    surfaceScalarField rhoPhiSum
    (
        IOobject("rhoPhiSum", runTime.timeName(), mesh_),
        mesh_,
        dimensionedScalar(rhoPhi_.dimensions(), Zero)
    );
    PtrList<surfaceScalarField> alphaPhiSums(alphaPhis.size());
    forAll(alphaPhiSums, i)
    {
        alphaPhiSums.set
        (
            i,
            new surfaceScalarField
            (
                IOobject
                (
                    "alphaPhiSum" + Foam::name(i), runTime.timeName(), mesh_
                ),
                mesh_,
                dimensionedScalar(alphaPhis[i].dimensions(), Zero)
            )
        );
    }
    const dimensionedScalar totalDeltaT = runTime.deltaT();

    for
    (
        subCycle<volScalarField> alphaSubCycle(phases_.alphas()[0], nSub);
        !(++alphaSubCycle).end();
    )
    {
        step();
        rhoPhiSum += (runTime.deltaT()/totalDeltaT)*rhoPhi_;
        forAll(alphaPhiSums, i)
        {
            alphaPhiSums[i] += (runTime.deltaT()/totalDeltaT)*alphaPhis[i];
        }
    }
    rhoPhi_ = rhoPhiSum;
    forAll(alphaPhiSums, i)
    {
        alphaPhis[i] = alphaPhiSums[i];
    }
}


// ************************************************************************* //
