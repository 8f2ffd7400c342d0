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
#include "profiling.H"
#include "syncTools.H"

// * * * * * * * * * * * * * * * Static Data * * * * * * * * * * * * * * * //

const Foam::Enum<Foam::granularTransport::stepFlux>
Foam::granularTransport::stepFluxNames
({
    { stepFlux::startOfStep, "startOfStep" },
    { stepFlux::midStep, "midStep" },
});


// * * * * * * * * * * * * Private Member Functions  * * * * * * * * * * * * //

void Foam::granularTransport::updateStepFlux()
{
    const dictionary& dict = mesh_.solverDict("alpha");
    midStep_ =
        granularInput::readEnum
        (
            dict, "transportFlux",
            stepFluxNames, stepFlux::startOfStep
        )
     == stepFlux::midStep;
    phiStart_.writeOpt() =
        midStep_ ? IOobject::AUTO_WRITE : IOobject::NO_WRITE;
    if (!midStep_)
    {
        return;
    }

    if (mesh_.topoChanging() || mesh_.moving())
    {
        const bool volumeChange =
            mesh_.topoChanging()
         || gMax(mag(1 - mesh_.V0().field()/mesh_.V().field())) > 1e-12;
        if (volumeChange)
        {
            FatalIOErrorInFunction(dict)
                << "Invalid value in dictionary " << dict.name()
                << ": transportFlux = midStep on a mesh whose cell volumes"
                << " change (the combination of the fluxes of two steps is"
                << " then not divergence-free): use startOfStep" << nl
                << exit(FatalIOError);
        }
    }

    const Time& runTime = mesh_.time();
    const label timeIndex = runTime.timeIndex();
    if (timeIndex != startTimeIndex_)
    {
        // The first transport of the step: from the fluxes at the starts of
        // the previous step (phiStart_) and of this one (phi_), linear in
        // time, at the middle of this step
        if (startTimeIndex_ == timeIndex - 1)
        {
            const scalar theta =
                0.5*runTime.deltaTValue()/runTime.deltaT0Value();
            phiStep_ = phi_ + theta*(phi_ - phiStart_);
        }
        else
        {
            phiStep_ = phi_;
        }
        phiStart_ = phi_;
        startTimeIndex_ = timeIndex;
    }
    else
    {
        // A later outer iteration: the mean of the step's start and the
        // previous iteration's end
        phiStep_ = 0.5*(phiStart_ + phi_);
    }
}


Foam::tmp<Foam::scalarField> Foam::granularTransport::explicitUpdate
(
    const volScalarField& alpha,
    const surfaceScalarField& alphaPhi,
    const surfaceScalarField* alphaPhi2
) const
{
    // The update of MULES::explicitSolve, without changing the field
    auto tpsi = tmp<scalarField>::New(alpha.oldTime().primitiveField());
    scalarField& psi = tpsi.ref();
    if (mesh_.moving())
    {
        psi *= mesh_.Vsc0()().field()/mesh_.Vsc()().field();
    }
    const tmp<surfaceScalarField> tflux
    (
        alphaPhi2 ? alphaPhi + *alphaPhi2 : tmp<surfaceScalarField>(alphaPhi)
    );
    psi -= mesh_.time().deltaTValue()
       *fvc::surfaceIntegrate(tflux())().primitiveField();
    return tpsi;
}


void Foam::granularTransport::fluxParts
(
    const surfaceScalarField& alphaPhi,
    scalarField& outgoing,
    scalarField& incoming
) const
{
    const labelUList& own = mesh_.owner();
    const labelUList& nei = mesh_.neighbour();

    outgoing = Zero;
    incoming = Zero;
    forAll(nei, facei)
    {
        const scalar f = alphaPhi[facei];
        const label from = f > 0 ? own[facei] : nei[facei];
        const label to = f > 0 ? nei[facei] : own[facei];
        outgoing[from] += mag(f);
        incoming[to] += mag(f);
    }
    forAll(mesh_.boundary(), patchi)
    {
        const labelUList& faceCells = mesh_.boundary()[patchi].faceCells();
        const fvsPatchScalarField& pf = alphaPhi.boundaryField()[patchi];
        forAll(faceCells, facei)
        {
            (pf[facei] > 0 ? outgoing : incoming)[faceCells[facei]] +=
                mag(pf[facei]);
        }
    }
    // per unit volume as fvc::surfaceIntegrate and MULES take it
    const scalarField dtByV(mesh_.time().deltaTValue()/mesh_.Vsc()().field());
    outgoing *= dtByV;
    incoming *= dtByV;
}


Foam::tmp<Foam::scalarField> Foam::granularTransport::boundsExcess
(
    const scalarField& psi
)
{
    return max(max(-psi, psi - 1), scalar(0));
}


Foam::label Foam::granularTransport::repairBounds
(
    PtrList<surfaceScalarField>& corrections,
    const PtrList<surfaceScalarField>& upwindPhis,
    const PtrList<scalarField>& upwindExcess,
    const bool remove
) const
{
    const scalar tol = 1e-12;
    const labelUList& own = mesh_.owner();
    const labelUList& nei = mesh_.neighbour();
    const label nInternal = mesh_.nInternalFaces();

    // The factor of each face's corrections, of every phase
    scalarField lambda(mesh_.nFaces(), 1.0);
    label nOut = 0;

    scalarField outgoing(mesh_.nCells());
    scalarField incoming(mesh_.nCells());
    forAll(corrections, i)
    {
        const scalarField psi
        (
            explicitUpdate(phases_[i], corrections[i], &upwindPhis[i])
        );
        const scalarField excess(boundsExcess(psi) - upwindExcess[i]);
        label nPhaseOut = 0;
        forAll(excess, celli)
        {
            nPhaseOut += excess[celli] > tol;
        }
        if (nPhaseOut == 0)
        {
            continue;
        }
        nOut += nPhaseOut;
        fluxParts(corrections[i], outgoing, incoming);

        // The factor of a cell's outgoing corrections (below 0) or of its
        // incoming ones (above 1) that takes away the excess
        scalarField lambdaOut(mesh_.nCells(), 1.0);
        scalarField lambdaIn(mesh_.nCells(), 1.0);
        forAll(excess, celli)
        {
            if (excess[celli] > tol)
            {
                scalarField& l = psi[celli] < 0 ? lambdaOut : lambdaIn;
                const scalar part =
                    psi[celli] < 0 ? outgoing[celli] : incoming[celli];
                l[celli] =
                    remove
                  ? 0
                  : max(1 - excess[celli]/max(part, VSMALL), scalar(0));
            }
        }

        const scalarField& corr = corrections[i].primitiveField();
        forAll(nei, facei)
        {
            const label from = corr[facei] > 0 ? own[facei] : nei[facei];
            const label to = corr[facei] > 0 ? nei[facei] : own[facei];
            lambda[facei] =
                min(lambda[facei], min(lambdaOut[from], lambdaIn[to]));
        }
        forAll(mesh_.boundary(), patchi)
        {
            const fvPatch& patch = mesh_.boundary()[patchi];
            const fvsPatchScalarField& pcorr =
                corrections[i].boundaryField()[patchi];
            forAll(pcorr, facei)
            {
                const label celli = patch.faceCells()[facei];
                scalar& l = lambda[patch.start() + facei];
                l = min
                (
                    l,
                    pcorr[facei] > 0 ? lambdaOut[celli] : lambdaIn[celli]
                );
            }
        }
    }
    reduce(nOut, sumOp<label>());
    if (nOut == 0)
    {
        return 0;
    }

    // Both sides of a processor or cyclic face take the smaller factor
    const label nBoundary = mesh_.nBoundaryFaces();
    scalarField lambdaB(SubField<scalar>(lambda, nBoundary, nInternal));
    syncTools::syncBoundaryFaceList(mesh_, lambdaB, minEqOp<scalar>());
    SubField<scalar>(lambda, nBoundary, nInternal) = lambdaB;

    for (surfaceScalarField& corr : corrections)
    {
        corr.primitiveFieldRef() *= SubField<scalar>(lambda, nInternal);
        forAll(mesh_.boundary(), patchi)
        {
            const fvPatch& patch = mesh_.boundary()[patchi];
            fvsPatchScalarField& pcorr = corr.boundaryFieldRef()[patchi];
            forAll(pcorr, facei)
            {
                pcorr[facei] *= lambda[patch.start() + facei];
            }
        }
    }
    return nOut;
}


void Foam::granularTransport::fluxes
(
    PtrList<surfaceScalarField>& alphaPhis,
    PtrList<surfaceScalarField>& relPhis,
    const bool rate
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
                fvc::flux(stepPhi(), alphas[i], alphaScheme)
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
        alphas, gravity_.unit(), air_, stepPhi(), pairs, phirs
    );
    pairFluxes_.add(alphas, pairs, phirs, alphaPhis, &relPhis);
    if (rate)
    {
        segregationRate_ =
            pairFluxes_.segregationRate(alphas, pairs, phirs);
    }
}


void Foam::granularTransport::limit
(
    PtrList<surfaceScalarField>& alphaPhis,
    const PtrList<surfaceScalarField>& upwindPhis
) const
{
    PtrList<volScalarField>& alphas = phases_.alphas();

    // multiphaseInterFoam's pass: each phase bounded, then the corrections
    // made to sum to zero
    forAll(alphas, i)
    {
        MULES::limit
        (
            1.0/mesh_.time().deltaTValue(),
            geometricOneField(),
            alphas[i],
            stepPhi(),
            alphaPhis[i],
            zeroField(),
            zeroField(),
            oneField(),
            zeroField(),
            true
        );
    }
    MULES::limitSum(alphaPhis);

    // limitSum scales corrections of one sign only, which can undo a
    // phase's bound where several phases meet (on the chute, a cell or two
    // at the surface near the inlet in every sub-cycle; on moving meshes).
    // Where the update would leave [0, 1] by more than 1e-12 beyond the
    // upwind update, the corrections of every phase on the faces that take
    // the cell out (its outgoing ones below 0, its incoming ones above 1)
    // are scaled down by the factor that brings it back, so that they still
    // sum to zero; a neighbour that this unbounds is seen to in the next
    // round.  From the tenth round on, those corrections are removed, which
    // ends the repair (a cell without corrections has the upwind update).
    // The upwind update itself leaves [0, 1] by the continuity error of phi
    // (about 1e-9 in the chute, within the pressure tolerance), which no
    // limiting can remove: hence the bound relative to it.
    PtrList<scalarField> upwindExcess(alphas.size());
    forAll(alphas, i)
    {
        upwindExcess.set
        (
            i,
            boundsExcess(explicitUpdate(alphas[i], upwindPhis[i]))
        );
    }
    for
    (
        label round = 0;
        repairBounds(alphaPhis, upwindPhis, upwindExcess, round >= 10);
        ++round
    )
    {}
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


void Foam::granularTransport::step(const bool last)
{
    const label nPhases = phases_.size();

    PtrList<surfaceScalarField> alphaPhis(nPhases);
    PtrList<surfaceScalarField> relPhis(nPhases);
    addProfiling(fluxesSection, "granular::phases::fluxes");
    fluxes(alphaPhis, relPhis, last);
    endProfiling(fluxesSection);

    PtrList<surfaceScalarField> upwindPhis(nPhases);
    forAll(upwindPhis, i)
    {
        upwindPhis.set
        (
            i,
            new surfaceScalarField
            (
                upwind<scalar>(mesh_, stepPhi()).flux(phases_[i])
            )
        );
    }
    addProfiling(limitSection, "granular::phases::limit");
    limit(alphaPhis, upwindPhis);
    endProfiling(limitSection);

    pairwiseFluxSum_.value() = max
    (
        pairwiseFluxSum_.value(), granularPairFluxes::fluxSum(relPhis)
    );
    limitedFluxSum_.value() = max
    (
        limitedFluxSum_.value(), granularPairFluxes::fluxSum(alphaPhis)
    );

    addProfiling(updateSection, "granular::phases::update");
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
    phiStart_
    (
        IOobject
        (
            "phiStepStart",
            mesh_.time().timeName(),
            mesh_,
            IOobject::READ_IF_PRESENT,
            IOobject::NO_WRITE
        ),
        phi
    ),
    startTimeIndex_
    (
        phiStart_.headerOk() ? mesh_.time().timeIndex() : -1
    ),
    phiStep_("phiStep", phi),
    midStep_(false),
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
    updateStepFlux();
    pairwiseFluxSum_.value() = 0;
    limitedFluxSum_.value() = 0;
    if (nSub <= 1)
    {
        step(true);
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

    // Every phase keeps the old time of the step through the sub-cycles
    // (subCycle<> keeps only that of the field it is given): a later outer
    // iteration then transports each phase from the start of the step
    // again, not on from where the previous iteration left it
    PtrList<subCycleField<volScalarField>> oldTimes(phases_.size());
    forAll(oldTimes, i)
    {
        oldTimes.set
        (
            i,
            new subCycleField<volScalarField>(phases_.alphas()[i])
        );
    }
    {
        subCycleTime subTime(const_cast<Time&>(runTime), nSub);
        forAll(oldTimes, i)
        {
            oldTimes[i].updateTimeIndex();
        }
        while (!(++subTime).end())
        {
            step(subTime.index() == nSub);
            rhoPhiSum += (runTime.deltaT()/totalDeltaT)*rhoPhi_;
            forAll(alphaPhiSums, i)
            {
                alphaPhiSums[i] +=
                    (runTime.deltaT()/totalDeltaT)*alphaPhis[i];
            }
        }
    }   // subTime ends first: oldTimes restore the old times at the
        // step's time index
    rhoPhi_ = rhoPhiSum;
    forAll(alphaPhiSums, i)
    {
        alphaPhis[i] = alphaPhiSums[i];
    }
}


// ************************************************************************* //
