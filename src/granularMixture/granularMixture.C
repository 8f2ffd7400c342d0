/*---------------------------------------------------------------------------*\
    granularSegregationFoam: coupled mu(I) rheology and size segregation
    Copyright (C) 2026 The granularSegregationFoam authors
    License: GNU General Public License v3 or later (see LICENSE)
\*---------------------------------------------------------------------------*/

#include "granularMixture.H"
#include "granularInput.H"
#include "wellPosedness.H"
#include "MULES.H"
#include "subCycle.H"
#include "upwind.H"
#include "localMax.H"
#include "fvcGrad.H"
#include "fvcFlux.H"
#include "fvcSnGrad.H"
#include "fvcSurfaceIntegrate.H"
#include "surfaceInterpolate.H"
#include "zeroGradientFvPatchFields.H"
#include "cyclicPolyPatch.H"
#include "processorCyclicPolyPatch.H"

// * * * * * * * * * * * * * * Static Data Members * * * * * * * * * * * * * //

namespace Foam
{
    defineTypeNameAndDebug(granularMixture, 0);
}

const Foam::Enum<Foam::granularMixture::sharpening>
Foam::granularMixture::sharpeningNames
({
    { sharpening::segregation, "segregation" },
    { sharpening::counterGradient, "counterGradient" },
    { sharpening::none, "none" },
});


const Foam::Enum<Foam::granularMixture::viscousStress>
Foam::granularMixture::viscousStressNames
({
    { viscousStress::explicitStress, "explicit" },
    { viscousStress::implicitStress, "implicit" },
});


namespace
{
    //- IOobject of a state field of the mixture
    Foam::IOobject stateIO
    (
        const Foam::fvMesh& mesh,
        const Foam::word& name,
        const bool write
    )
    {
        using namespace Foam;
        return IOobject
        (
            name,
            mesh.time().timeName(),
            mesh,
            IOobject::NO_READ,
            write ? IOobject::AUTO_WRITE : IOobject::NO_WRITE
        );
    }
}

namespace
{
    //- Number of values (over all processors) with a non-finite component
    template<class Type>
    Foam::label nonFinite(const Foam::Field<Type>& values)
    {
        using namespace Foam;
        label n = 0;
        for (const Type& v : values)
        {
            for (direction c = 0; c < pTraits<Type>::nComponents; ++c)
            {
                if (!std::isfinite(component(v, c)))
                {
                    ++n;
                    break;
                }
            }
        }
        return returnReduce(n, sumOp<label>());
    }
}

#define STATE_FIELD(name, dims, write)                                        \
    stateIO(mesh_, name, write),                                              \
    mesh_,                                                                    \
    dimensionedScalar(dims, Zero),                                            \
    zeroGradientFvPatchScalarField::typeName


// * * * * * * * * * * * * Private Member Functions  * * * * * * * * * * * * //

void Foam::granularMixture::readAir()
{
    const dictionary& dict = granularInput::subDict
    (
        *this, "air", "name, rho, eta and the sharpening of the air"
    );

    airName_ = dict.getOrDefault<word>("name", "air");
    rhoAir_ = granularInput::readPositive(dict, "rho", dimDensity);
    etaAir_ = granularInput::readPositive(dict, "eta", dimPressure*dimTime);
    sharpening_ =
        sharpeningNames.getOrDefault("sharpening", dict, sharpening::segregation);

    fAir_ = dimensionedScalar(dimVelocity, Zero);
    eAir_ = Zero;
    cAlpha_ = 0;

    if (sharpening_ == sharpening::segregation)
    {
        fAir_ = granularInput::readNonNegative(dict, "f", dimVelocity);

        vector e(Zero);
        const word d
        (
            granularInput::readVectorOrWord
            (
                dict, "direction", {"gravity", "antiGravity"}, e
            )
        );
        if (d == "gravity")
        {
            eAir_ = gHat();
        }
        else if (d == "antiGravity")
        {
            eAir_ = -gHat();
        }
        else if (mag(e) < SMALL)
        {
            FatalIOErrorInFunction(dict)
                << "Invalid value of keyword 'direction' in dictionary "
                << dict.name() << ": direction = " << e
                << " (a vector of nonzero length)" << nl
                << exit(FatalIOError);
        }
        else
        {
            eAir_ = e/mag(e);
        }
        if (fAir_.value() > 0 && mag(eAir_) < SMALL)
        {
            FatalIOErrorInFunction(dict)
                << "Invalid value of keyword 'direction' in dictionary "
                << dict.name() << ": direction = " << d
                << " but g = " << g_.value() << " is zero" << nl
                << exit(FatalIOError);
        }
    }
    else if (sharpening_ == sharpening::counterGradient)
    {
        cAlpha_ = granularInput::readNonNegative(dict, "cAlpha").value();
    }
}


void Foam::granularMixture::checkFractions() const
{
    const scalar tol = 1e-6;
    scalarField sum(mesh_.nCells(), Zero);

    for (const volScalarField& alpha : alphas_)
    {
        const scalar lo = gMin(alpha.primitiveField());
        const scalar hi = gMax(alpha.primitiveField());
        if (lo < -tol || hi > 1 + tol)
        {
            FatalErrorInFunction
                << "Invalid initial field " << alpha.objectPath()
                << ": values in [" << lo << ", " << hi << "], outside [0, 1]"
                << nl << exit(FatalError);
        }
        sum += alpha.primitiveField();
    }

    const scalar err = gMax(mag(sum - 1.0)());
    if (err > tol)
    {
        FatalErrorInFunction
            << "Invalid initial phase fractions in "
            << mesh_.time().timePath() << ": the fractions of "
            << alphas_.size() << " phases (alpha.*) must sum to 1, but"
            << " |sum - 1| reaches " << err << " (tolerance " << tol << ")"
            << nl << exit(FatalError);
    }
}


void Foam::granularMixture::checkPhaseFiles() const
{
    // Each phase fraction is dimensionless
    for (const volScalarField& alpha : alphas_)
    {
        if (alpha.dimensions() != dimless)
        {
            FatalIOError
            (
                FUNCTION_NAME, __FILE__, __LINE__, alpha.objectPath()
            )   << "Invalid value of keyword 'dimensions' in file "
                << alpha.objectPath() << ": dimensions = "
                << alpha.dimensions() << "; a phase fraction is"
                << " dimensionless, " << dimless << nl
                << exit(FatalIOError);
        }
    }

    // A fraction file that no phase reads: a misspelt or left-over phase
    wordList names(alphas_.size());
    forAll(alphas_, i)
    {
        names[i] = alphas_[i].name();
    }
    const fileName dir(mesh_.time().timePath());
    for (const fileName& f : readDir(dir, fileName::FILE))
    {
        const word name(f.ext() == "gz" ? f.lessExt() : f);
        if (name.starts_with("alpha.") && !names.found(name))
        {
            WarningInFunction
                << dir/f << " is not read: it matches no phase of "
                << this->objectPath() << " (the phases read: " << names
                << ")" << endl;
        }
    }
}


void Foam::granularMixture::calcG()
{
    surfaceScalarField geom(mesh_.magSf()*mesh_.deltaCoeffs());
    G_ = 0.5*fvc::surfaceSum(geom)().primitiveField()/mesh_.V().field();
}


void Foam::granularMixture::calcMixture()
{
    const volScalarField& alphaAir = alphas_[0];
    const dimensionedScalar rhoGrains(rheology_.rhoGrains());

    // (4.7a,b): the grains share one density and one viscosity
    rho_ = alphaAir*rhoAir_ + (1 - alphaAir)*rhoGrains;
    eta_ = alphaAir*etaAir_ + (1 - alphaAir)*etaGranular_;
    nu_ = eta_/rho_;
}


Foam::vector Foam::granularMixture::gHat() const
{
    const scalar magg = mag(g_.value());
    return magg > SMALL ? g_.value()/magg : vector::zero;
}


Foam::vector Foam::granularMixture::bodyForceGravity() const
{
    const List<vector> listed
    (
        getOrDefault<List<vector>>("bodyForceDirections", List<vector>())
    );
    for (const vector& d : listed)
    {
        if (mag(d) < SMALL)
        {
            FatalIOErrorInFunction(*this)
                << "Invalid value of keyword 'bodyForceDirections' in "
                << "dictionary " << name() << ": " << listed
                << " (a direction of zero length)" << nl
                << exit(FatalIOError);
        }
    }

    // Orthonormal basis of the separation vectors of the cyclic patches
    // and of the listed directions
    List<vector> basis;
    auto add = [&basis](vector s)
    {
        for (const vector& b : basis)
        {
            s -= (s & b)*b;
        }
        if (mag(s) > SMALL)
        {
            basis.append(s/mag(s));
        }
    };
    for (const polyPatch& pp : mesh_.boundaryMesh())
    {
        const auto* cpp = isA<cyclicPolyPatch>(pp);
        vector s(Zero);
        if (cpp && !isA<processorCyclicPolyPatch>(pp))
        {
            if (cpp->size() && cpp->separated())
            {
                s = cpp->separation()[0];
            }
        }
        reduce(s, maxMagSqrOp<vector>());
        add(s);
    }
    for (const vector& d : listed)
    {
        add(d);
    }

    vector gb(Zero);
    for (const vector& b : basis)
    {
        gb += (g_.value() & b)*b;
    }
    return gb;
}


void Foam::granularMixture::zeroUncoupled(surfaceScalarField& sf)
{
    for (fvsPatchScalarField& psf : sf.boundaryFieldRef())
    {
        if (!psf.coupled())
        {
            psf = Zero;
        }
    }
}


void Foam::granularMixture::relativeFluxes
(
    List<labelPair>& pairs,
    PtrList<surfaceScalarField>& phirs
) const
{
    pairs.clear();
    phirs.clear();

    // Grain pairs: the smaller phase moves along g (2.13), (2.19)
    const surfaceScalarField gSf(gHat() & mesh_.Sf());
    for (label k = 0; k < segregation_.size(); ++k)
    {
        const segregationVelocity& law = segregation_[k];
        const label i = 1 + law.small();
        const label j = 1 + law.large();
        pairs.append(labelPair(i, j));
        if (law.type() == "constant")
        {
            phirs.append(new surfaceScalarField(fvc::interpolate(f_[k])*gSf));
            continue;
        }

        // f of a law that depends on the state is a property of the pair's
        // grains: on a face it is their fraction-weighted mean of the two
        // cells' values.  A plain mean would carry into the grains at the
        // free surface the f of the air cell above, where p = pMin and
        // Trewhela's (3.9) with C = 0 gives 1e7 m/s.
        const volScalarField aij(alphas_[i] + alphas_[j]);
        const surfaceScalarField aijf(fvc::interpolate(aij));
        phirs.append
        (
            new surfaceScalarField
            (
                (
                    pos(aijf - SMALL)*fvc::interpolate(aij*f_[k])
                   /max(aijf, dimensionedScalar("small", dimless, SMALL))
                  + neg0(aijf - SMALL)*fvc::interpolate(f_[k])
                )*gSf
            )
        );
    }

    // Air with each grain phase
    if (sharpening_ == sharpening::segregation && fAir_.value() > 0)
    {
        const surfaceScalarField phirAir(fAir_*(eAir_ & mesh_.Sf()));
        for (label i = 1; i < alphas_.size(); ++i)
        {
            pairs.append(labelPair(0, i));
            phirs.append(new surfaceScalarField(phirAir));
        }
    }
    else if (sharpening_ == sharpening::counterGradient && cAlpha_ > 0)
    {
        // (4.9), as multiphaseInterFoam's compression
        surfaceScalarField phic(mag(phi_/mesh_.magSf()));
        phic = min(cAlpha_*phic, max(phic));

        const dimensionedScalar deltaN
        (
            "deltaN",
            1e-8/pow(average(mesh_.V()), 1.0/3.0)
        );

        const volScalarField& a = alphas_[0];
        for (label i = 1; i < alphas_.size(); ++i)
        {
            const volScalarField& b = alphas_[i];
            surfaceVectorField gradf
            (
                fvc::interpolate(b)*fvc::interpolate(fvc::grad(a))
              - fvc::interpolate(a)*fvc::interpolate(fvc::grad(b))
            );
            pairs.append(labelPair(0, i));
            phirs.append
            (
                new surfaceScalarField
                (
                    phic*((gradf/(mag(gradf) + deltaN)) & mesh_.Sf())
                )
            );
        }
    }

    for (surfaceScalarField& phir : phirs)
    {
        zeroUncoupled(phir);
    }
}


Foam::scalar Foam::granularMixture::fluxSum
(
    const PtrList<surfaceScalarField>& fluxes
)
{
    surfaceScalarField sum(fluxes[0]);
    scalar largest = max(mag(fluxes[0])).value();
    for (label i = 1; i < fluxes.size(); ++i)
    {
        sum += fluxes[i];
        largest = max(largest, max(mag(fluxes[i])).value());
    }
    return max(mag(sum)).value()/max(largest, VSMALL);
}


Foam::tmp<Foam::scalarField> Foam::granularMixture::boundsExcess
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


bool Foam::granularMixture::outOfBounds
(
    const PtrList<surfaceScalarField>& corrections,
    const PtrList<surfaceScalarField>& upwindPhis,
    const PtrList<scalarField>& upwindExcess,
    const scalar tol
) const
{
    bool out = false;
    forAll(alphas_, i)
    {
        const scalarField excess
        (
            boundsExcess(alphas_[i], corrections[i] + upwindPhis[i])
          - upwindExcess[i]
        );
        out = out || max(excess) > tol;
    }
    return returnReduce(out, orOp<bool>());
}


Foam::tmp<Foam::scalarField> Foam::granularMixture::segregationRate
(
    const List<labelPair>& pairs,
    const PtrList<surfaceScalarField>& phirs
) const
{
    auto trate = tmp<scalarField>::New(mesh_.nCells(), Zero);
    scalarField& rate = trate.ref();
    forAll(pairs, k)
    {
        // The flux f phi^i phi^j moves at most at f (phi^i + phi^j): a grain
        // pair's rate is weighted by its fractions (the larger of the two
        // cells of a face), so a law unbounded where there are no grains,
        // Trewhela's (3.9) with C = 0 as p -> 0, does not hold the step in
        // the air.  The air pairs (f a constant) keep the plain bound.
        if (k < segregation_.size())
        {
            const volScalarField aij
            (
                alphas_[pairs[k].first()] + alphas_[pairs[k].second()]
            );
            rate = max
            (
                rate,
                fvc::surfaceSum
                (
                    mag(phirs[k])
                   *localMax<scalar>(mesh_).interpolate(aij)
                )().primitiveField()
            );
        }
        else
        {
            rate = max(rate, fvc::surfaceSum(mag(phirs[k]))().primitiveField());
        }
    }
    rate *= 0.5/mesh_.V().field();
    return trate;
}


void Foam::granularMixture::updateSegregationRate()
{
    List<labelPair> pairs;
    PtrList<surfaceScalarField> phirs;
    relativeFluxes(pairs, phirs);
    segregationRate_ = segregationRate(pairs, phirs);
}


void Foam::granularMixture::solveAlphas()
{
    const word alphaScheme("div(phi,alpha)");
    const word alpharScheme("div(phirb,alpha)");
    const label nPhases = alphas_.size();

    // The bounded-advection, segregation and diffusion fluxes of each phase
    PtrList<surfaceScalarField> alphaPhis(nPhases);
    forAll(alphas_, i)
    {
        alphaPhis.set
        (
            i,
            new surfaceScalarField
            (
                "phiAlpha." + alphas_[i].name(),
                fvc::flux(phi_, alphas_[i], alphaScheme)
            )
        );
    }

    // The relative (segregation and diffusion) flux of each phase, kept
    // apart for the check of (2.12) under the debug switch only: the
    // fluxes are added to alphaPhis pair by pair as before, because the
    // chute's outflow at the implicit stress's large steps is sensitive
    // to the order of the sums (a change of that order alone left it
    // unsteady at 25 s)
    PtrList<surfaceScalarField> relPhis(debug ? nPhases : 0);
    forAll(relPhis, i)
    {
        relPhis.set
        (
            i,
            new surfaceScalarField
            (
                "relPhi." + alphas_[i].name(),
                0*alphaPhis[i]
            )
        );
    }

    // (2.13): one flux per pair, +F for i and -F for j
    List<labelPair> pairs;
    PtrList<surfaceScalarField> phirs;
    relativeFluxes(pairs, phirs);

    forAll(pairs, k)
    {
        const volScalarField& ai = alphas_[pairs[k].first()];
        const volScalarField& aj = alphas_[pairs[k].second()];
        const surfaceScalarField F
        (
            fvc::flux(-fvc::flux(-phirs[k], aj, alpharScheme), ai, alpharScheme)
        );
        alphaPhis[pairs[k].first()] += F;
        alphaPhis[pairs[k].second()] -= F;
        if (debug)
        {
            relPhis[pairs[k].first()] += F;
            relPhis[pairs[k].second()] -= F;
        }
    }
    segregationRate_ = segregationRate(pairs, phirs);

    // (2.15): D^i = D_ij (phi^j grad phi^i - phi^i grad phi^j), a flux -D^i
    for (label k = 0; k < diffusion_.size(); ++k)
    {
        const label i = 1 + diffusion_[k].small();
        const label j = 1 + diffusion_[k].large();
        const volScalarField& ai = alphas_[i];
        const volScalarField& aj = alphas_[j];

        surfaceScalarField Fd
        (
            -fvc::interpolate(D_[k])*mesh_.magSf()
           *(
                fvc::interpolate(aj)*fvc::snGrad(ai)
              - fvc::interpolate(ai)*fvc::snGrad(aj)
            )
        );
        zeroUncoupled(Fd);
        alphaPhis[i] += Fd;
        alphaPhis[j] -= Fd;
        if (debug)
        {
            relPhis[i] += Fd;
            relPhis[j] -= Fd;
        }
    }

    // Bound each phase, then make the corrections sum to zero.  limitSum
    // scales corrections of one sign only, which can undo a phase's bound
    // where several phases meet (seen on moving meshes): while the update
    // would leave [0, 1] by more than 1e-12 beyond the upwind update, the
    // pair is repeated, each pass shrinking the corrections towards the
    // bounded upwind fluxes.  One pass, multiphaseInterFoam's, is the rule.
    // The upwind update itself leaves [0, 1] by the continuity error of
    // phi (about 1e-9 in the chute, within the pressure tolerance): no
    // limiting can remove that part, and the passes would repeat in vain.
    const label nPasses =
        mesh_.solverDict("alpha").getOrDefault<label>("nLimitSumPasses", 10);
    if (nPasses < 1)
    {
        granularInput::invalid
        (
            mesh_.solverDict("alpha"), "nLimitSumPasses", nPasses, ">= 1"
        );
    }
    PtrList<surfaceScalarField> upwindPhis(nPhases);
    forAll(alphas_, i)
    {
        upwindPhis.set
        (
            i,
            new surfaceScalarField(upwind<scalar>(mesh_, phi_).flux(alphas_[i]))
        );
    }
    PtrList<scalarField> upwindExcess(nPhases);
    forAll(alphas_, i)
    {
        upwindExcess.set(i, boundsExcess(alphas_[i], upwindPhis[i]));
    }
    label nDone = 0;
    for (label pass = 0; pass < nPasses; ++pass)
    {
        forAll(alphas_, i)
        {
            if (pass > 0)
            {
                alphaPhis[i] += upwindPhis[i];
            }
            MULES::limit
            (
                1.0/mesh_.time().deltaTValue(),
                geometricOneField(),
                alphas_[i],
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
        nDone = pass + 1;

        if (!outOfBounds(alphaPhis, upwindPhis, upwindExcess, 1e-12))
        {
            break;
        }
    }
    DebugInfo<< "MULES limit/limitSum passes: " << nDone << endl;

    if (debug)
    {
        Info<< "    flux sums (2.12): pairwise " << fluxSum(relPhis)
            << " limited " << fluxSum(alphaPhis) << endl;
    }

    rhoPhi_ = dimensionedScalar(rhoPhi_.dimensions(), Zero);
    const dimensionedScalar rhoGrains(rheology_.rhoGrains());

    scalarField sumAlpha(mesh_.nCells(), Zero);
    forAll(alphas_, i)
    {
        volScalarField& alpha = alphas_[i];
        surfaceScalarField& alphaPhi = alphaPhis[i];
        alphaPhi += upwindPhis[i];

        MULES::explicitSolve(geometricOneField(), alpha, alphaPhi);

        rhoPhi_ += alphaPhi*(i == 0 ? rhoAir_ : rhoGrains);
        alphaPhis_[i] = alphaPhi;
        sumAlpha += alpha.primitiveField();
    }

    // Remove the round-off drift of the sum, as multiphaseInterFoam does
    const scalarField sumCorr(1.0 - sumAlpha);
    for (volScalarField& alpha : alphas_)
    {
        alpha.primitiveFieldRef() += alpha.primitiveField()*sumCorr;
        alpha.correctBoundaryConditions();
    }
}


// * * * * * * * * * * * * * * * * Constructors  * * * * * * * * * * * * * * //

Foam::granularMixture::granularMixture
(
    const volVectorField& U,
    const surfaceScalarField& phi
)
:
    IOdictionary
    (
        IOobject
        (
            "granularProperties",
            U.time().constant(),
            U.db(),
            IOobject::MUST_READ_IF_MODIFIED,
            IOobject::NO_WRITE
        )
    ),
    transportModel(),
    mesh_(U.mesh()),
    U_(U),
    phi_(phi),
    g_(meshObjects::gravity::New(mesh_.time())),
    rheology_(*this),
    airName_(),
    rhoAir_(dimDensity, Zero),
    etaAir_(dimPressure*dimTime, Zero),
    sharpening_(sharpening::segregation),
    fAir_(dimVelocity, Zero),
    eAir_(Zero),
    cAlpha_(0),
    alphas_(),
    segregation_(*this, "segregation", rheology_),
    diffusion_(*this, "diffusion", rheology_),
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
    pGranular_(STATE_FIELD("pGranular", dimPressure, true)),
    shearRate_(STATE_FIELD("shearRate", inv(dimTime), true)),
    dbar_(STATE_FIELD("dbar", dimLength, true)),
    I_(STATE_FIELD("I", dimless, true)),
    etaGranular_
    (
        STATE_FIELD("etaGranular", dimPressure*dimTime, true)
    ),
    illPosed_(STATE_FIELD("illPosed", dimless, true)),
    rho_(STATE_FIELD("granularMixture:rho", dimDensity, false)),
    eta_(STATE_FIELD("granularMixture:eta", dimPressure*dimTime, false)),
    nu_(STATE_FIELD("granularMixture:nu", dimViscosity, false)),
    G_(),
    segregationRate_(mesh_.nCells(), Zero),
    gBody_(Zero),
    tensionWarning_(readTensionWarning()),
    grainPressureMin_
    (
        IOobject
        (
            "grainPressureMin",
            mesh_.time().constant(),
            mesh_,
            IOobject::NO_READ,
            IOobject::NO_WRITE
        ),
        dimensionedScalar("grainPressureMin", dimPressure, VGREAT)
    )
{
    readAir();

    const wordList& grains = rheology_.names();
    if (grains.found(airName_))
    {
        FatalIOErrorInFunction(*this)
            << "Invalid value of keyword 'name' in dictionary "
            << subDict("air").name() << ": name = " << airName_
            << " is also a grain phase " << grains << nl
            << exit(FatalIOError);
    }

    alphas_.setSize(1 + grains.size());
    forAll(alphas_, i)
    {
        const word phaseName(i == 0 ? airName_ : grains[i - 1]);
        alphas_.set
        (
            i,
            new volScalarField
            (
                IOobject
                (
                    IOobject::groupName("alpha", phaseName),
                    mesh_.time().timeName(),
                    mesh_,
                    IOobject::MUST_READ,
                    IOobject::AUTO_WRITE
                ),
                mesh_
            )
        );
    }
    checkPhaseFiles();
    checkFractions();

    alphaPhis_.setSize(alphas_.size());
    forAll(alphaPhis_, i)
    {
        alphaPhis_.set
        (
            i,
            new surfaceScalarField
            (
                IOobject
                (
                    "alphaPhi." + alphas_[i].name(),
                    mesh_.time().timeName(),
                    mesh_,
                    IOobject::NO_READ,
                    IOobject::NO_WRITE
                ),
                mesh_,
                dimensionedScalar(dimVolume/dimTime, Zero)
            )
        );
    }

    forAll(segregation_, k)
    {
        f_.append
        (
            new volScalarField(STATE_FIELD("granularMixture:f" + Foam::name(k), dimVelocity, false))
        );
    }
    forAll(diffusion_, k)
    {
        D_.append
        (
            new volScalarField(STATE_FIELD("granularMixture:D" + Foam::name(k), dimArea/dimTime, false))
        );
    }

    calcG();

    // The density of the initial fractions: createFields.H builds p as
    // p_rgh + rho*gh before the first rheology, which evaluates with that p
    calcMixture();

    gBody_ = bodyForceGravity();
    if (mag(gBody_) > 0)
    {
        Info<< "Gravity along the cyclic directions and bodyForceDirections "
            << gBody_
            << " acts as a body force; gh uses " << gHydrostatic().value()
            << nl << endl;
    }
}


#undef STATE_FIELD

// * * * * * * * * * * * * * * * Member Functions  * * * * * * * * * * * * * //

Foam::dimensionedVector Foam::granularMixture::gHydrostatic() const
{
    return dimensionedVector("g", g_.dimensions(), g_.value() - gBody_);
}


Foam::tmp<Foam::surfaceScalarField>
Foam::granularMixture::surfaceTensionForce() const
{
    return
        fvc::interpolate(rho_)
       *(dimensionedVector("gb", g_.dimensions(), gBody_) & mesh_.Sf())
       /mesh_.magSf();
}


Foam::tmp<Foam::volScalarField> Foam::granularMixture::nearInterface() const
{
    auto tnear = tmp<volScalarField>::New
    (
        IOobject("nearInterface", mesh_.time().timeName(), mesh_),
        mesh_,
        dimensionedScalar(dimless, Zero)
    );

    for (const volScalarField& alpha : alphas_)
    {
        tnear.ref() = max(tnear(), pos0(alpha - 0.01)*pos0(0.99 - alpha));
    }
    return tnear;
}


Foam::granularMixture::cflParts
Foam::granularMixture::cfl
(
    const scalar deltaT,
    const bool viscousLimit
) const
{
    if (mesh_.changing())
    {
        const_cast<granularMixture&>(*this).calcG();
    }

    const scalarField conv
    (
        0.5*fvc::surfaceSum(mag(phi_))().primitiveField()/mesh_.V().field()
    );
    const scalarField visc(nu_.primitiveField()*G_);

    scalarField diff(mesh_.nCells(), Zero);
    for (const volScalarField& D : D_)
    {
        diff += D.primitiveField()*G_;
    }

    // Sub-cycled transport: the momentum's part alone limits the step here,
    // the transport's part is divided among the sub-cycles (solve())
    const label nSubMax = maxAlphaSubCycles();
    const scalarField transport(conv + segregationRate_ + diff);
    scalarField total(nSubMax ? conv : transport);
    if (viscousLimit)
    {
        total += visc;
    }
    const scalar maxTotal = gMax(total);

    cflParts parts;
    parts.convective = gMax(conv)*deltaT;
    parts.viscous = gMax(visc)*deltaT;
    parts.segregation = gMax(segregationRate_)*deltaT;
    parts.diffusion = gMax(diff)*deltaT;
    parts.total = maxTotal*deltaT;
    parts.maxSubCycles = nSubMax;
    parts.transport = gMax(transport)*deltaT;

    // The largest part in the cell of the largest total (any processor)
    FixedList<scalar, 4> local(Zero);
    if (total.size())
    {
        const label c = findMax(total);
        local =
        {
            conv[c],
            viscousLimit ? visc[c] : 0,
            nSubMax ? 0 : segregationRate_[c],
            nSubMax ? 0 : diff[c]
        };
        if (total[c] < maxTotal)
        {
            local = Zero;
        }
    }
    for (scalar& x : local)
    {
        reduce(x, maxOp<scalar>());
    }
    static const wordList partNames
        ({"convective", "viscous", "segregation", "diffusion"});
    parts.limiting = partNames[findMax(local)];

    return parts;
}


Foam::granularMixture::viscousStress
Foam::granularMixture::readViscousStress(const pimpleControl& pimple)
{
    const dictionary& dict = pimple.dict();
    const viscousStress v = viscousStressNames.getOrDefault
    (
        "viscousStress", dict, viscousStress::explicitStress
    );
    if (v == viscousStress::implicitStress && !pimple.momentumPredictor())
    {
        FatalIOErrorInFunction(dict)
            << "Invalid value of keyword 'viscousStress' in dictionary "
            << dict.name() << ": viscousStress = implicit needs"
            << " momentumPredictor yes (without the predictor the stress"
            << " acts explicitly through H(U))" << nl
            << exit(FatalIOError);
    }

    Info<< "Viscous stress: " << viscousStressNames[v]
        << (v == viscousStress::implicitStress
            ? " (the viscous part of (4.11) does not limit Delta t)"
            : " (Delta t limited by the whole of (4.11))")
        << nl << endl;

    return v;
}


Foam::scalar Foam::granularMixture::airPressureLevel
(
    const volScalarField& p
) const
{
    // The mean of p - rho^a g.x over the pure-air cells
    const scalarField pAir
    (
        p.primitiveField()
      - rhoAir_.value()*(gHydrostatic().value() & mesh_.C().primitiveField())
    );
    const scalarField V
    (
        mesh_.V().field()*pos0(alphas_[0].primitiveField() - 0.99)
    );
    const scalar volAir = gSum(V);
    if (volAir > 0)
    {
        return gSum(V*pAir)/volAir;
    }

    // No air (a domain full of grains): the smallest value, so that the
    // grains' pressure vanishes where it is lowest, as under a free surface,
    // and is positive elsewhere
    return gMin(pAir);
}


void Foam::granularMixture::levelPressure
(
    volScalarField& p,
    volScalarField& p_rgh,
    const scalar pRefValue
) const
{
    const dimensionedScalar shift
    (
        "shift",
        p.dimensions(),
        pRefValue - airPressureLevel(p)
    );
    p += shift;
    p_rgh += shift;
}


Foam::tmp<Foam::scalarField> Foam::granularMixture::rheologyPressure
(
    const volScalarField& p,
    const bool closed
) const
{
    if (!closed)
    {
        return tmp<scalarField>::New(p.primitiveField());
    }
    return
        p.primitiveField()
      - rhoAir_.value()*(gHydrostatic().value() & mesh_.C().primitiveField())
      - airPressureLevel(p);
}


Foam::dimensionedScalar Foam::granularMixture::readTensionWarning() const
{
    return granularInput::readNonNegativeOrDefault
    (
        *this, "tensionWarning", dimPressure, 1
    );
}


Foam::scalar Foam::granularMixture::reportGrainPressure
(
    const volScalarField& p,
    const bool closed
)
{
    const scalarField pg(rheologyPressure(p, closed));
    const scalarField& air = alphas_[0].primitiveField();
    scalar lowest = GREAT;
    forAll(pg, celli)
    {
        if (air[celli] < 0.5)
        {
            lowest = min(lowest, pg[celli]);
        }
    }
    reduce(lowest, minOp<scalar>());
    if (lowest == GREAT)
    {
        grainPressureMin_.value() = VGREAT;
        return lowest;
    }
    grainPressureMin_.value() = lowest;

    Info<< "Grain pressure seen by the rheology: min = " << lowest << " Pa";
    if (lowest < -tensionWarning_.value())
    {
        Info<< ": tension in the grains, below -tensionWarning "
            << tensionWarning_.value() << " Pa (" << name()
            << "); the rheology sees p_min there";
    }
    Info<< endl;
    return lowest;
}


void Foam::granularMixture::correctRheology
(
    const volScalarField& p,
    const bool closed
)
{
    const label nCells = mesh_.nCells();

    pGranular_.primitiveFieldRef() =
        max(rheologyPressure(p, closed), rheology_.pMin().value());
    pGranular_.correctBoundaryConditions();

    // (2.4): |D| of the previous iterate of U, shear rate 2|D|
    scalarField normD(nCells);
    rheology_.strainRateNorm(symm(fvc::grad(U_))().primitiveField(), normD);
    shearRate_.primitiveFieldRef() = 2*normD;

    // Grain-volume fractions and (3.1)
    PtrList<scalarField> w;
    grainFractions(w);
    UPtrList<const scalarField> wc(w.size());
    forAll(w, k)
    {
        wc.set(k, &w[k]);
    }
    rheology_.meanDiameter(wc, dbar_.primitiveFieldRef());

    // (3.2), (3.3)/(3.4), (2.3) with (4.12), and (2.6)
    const scalarField& pg = pGranular_.primitiveField();
    rheology_.inertialNumber(normD, pg, dbar_.primitiveField(), I_.primitiveFieldRef());

    scalarField mu(nCells);
    scalarField dmudI(nCells);
    rheology_.friction(I_.primitiveField(), wc, mu, &dmudI);
    rheology_.viscosity(mu, pg, normD, etaGranular_.primitiveFieldRef());
    wellPosedness::indicator
    (
        I_.primitiveField(), mu, dmudI, illPosed_.primitiveFieldRef()
    );

    // Segregation and diffusion of the grain pairs (section 3.3)
    const granularState state
    {
        shearRate_.primitiveField(), pg, dbar_.primitiveField(), wc,
        mag(g_.value())
    };
    forAll(f_, k)
    {
        segregation_[k].f(state, f_[k].primitiveFieldRef());
        f_[k].correctBoundaryConditions();
    }
    forAll(D_, k)
    {
        diffusion_[k].D(state, D_[k].primitiveFieldRef());
        D_[k].correctBoundaryConditions();
    }

    for
    (
        volScalarField* fld
      : {&shearRate_, &dbar_, &I_, &etaGranular_, &illPosed_}
    )
    {
        fld->correctBoundaryConditions();
    }

    calcMixture();
}


void Foam::granularMixture::checkFinite
(
    const volVectorField& U,
    const volScalarField& p
) const
{
    DynamicList<word> bad;
    DynamicList<label> n;
    const auto check = [&](const word& name, const label k)
    {
        if (k)
        {
            bad.append(name);
            n.append(k);
        }
    };
    check(U.name(), nonFinite(U.primitiveField()));
    check(p.name(), nonFinite(p.primitiveField()));
    for (const volScalarField& alpha : alphas_)
    {
        check(alpha.name(), nonFinite(alpha.primitiveField()));
    }

    if (bad.size())
    {
        FatalErrorInFunction
            << "Non-finite values (NaN or Inf) at time "
            << mesh_.time().timeName() << " in " << bad << ", in "
            << n << " cells: stopping before they are written" << nl
            << exit(FatalError);
    }
}


void Foam::granularMixture::grainFractions(PtrList<scalarField>& c) const
{
    UPtrList<const scalarField> grainAlphas(alphas_.size() - 1);
    for (label i = 1; i < alphas_.size(); ++i)
    {
        grainAlphas.set(i - 1, &alphas_[i].primitiveField());
    }
    rheology_.grainFractions(grainAlphas, c);
}


Foam::scalar Foam::granularMixture::segregationIndex() const
{
    const label nGrains = alphas_.size() - 1;
    if (nGrains < 2)
    {
        return -1;
    }

    // The fractions clipped at zero: MULES leaves round-off below zero
    // (-1e-13) where it undershoots, in the air above all.  The weight of a
    // cell is its grain volume, the concentrations c^i those of the
    // rheology, in [0, 1] and uniform where there are no grains.
    scalarField alphaG(mesh_.nCells(), Zero);
    for (label i = 1; i < alphas_.size(); ++i)
    {
        alphaG += max(alphas_[i].primitiveField(), scalar(0));
    }
    const scalarField w(mesh_.V().field()*alphaG);
    const scalar W = gSum(w);
    if (W <= VSMALL)
    {
        return -1;
    }

    PtrList<scalarField> c;
    grainFractions(c);
    scalar variance = 0;
    scalar mixed = 0;
    for (const scalarField& ci : c)
    {
        const scalar cMean = gSum(w*ci)/W;
        variance += gSum(w*sqr(ci - cMean))/W;
        mixed += cMean*(1 - cMean);
    }

    // variance sums terms >= 0 (the weights are); max keeps the root real
    // whatever the round-off
    return mixed > SMALL ? Foam::sqrt(max(variance, scalar(0))/mixed) : 0;
}


void Foam::granularMixture::report() const
{
    Info<< "Phase volumes:";
    for (const volScalarField& alpha : alphas_)
    {
        Info<< ' ' << alpha.name() << " = "
            << gSum(mesh_.V().field()*alpha.primitiveField());
    }
    Info<< nl;

    const scalar S = segregationIndex();
    if (S >= 0)
    {
        Info<< "Segregation index (0 mixed, 1 segregated) = " << S << nl;
    }
}


Foam::label Foam::granularMixture::maxAlphaSubCycles() const
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


Foam::label Foam::granularMixture::nAlphaSubCycles() const
{
    const Time& runTime = mesh_.time();
    const dictionary& dict = mesh_.solverDict("alpha");

    const label nMax = maxAlphaSubCycles();
    if (nMax)
    {
        // As many as keep each sub-cycle's transport part within maxAlphaCo
        const scalar maxAlphaCo =
            runTime.controlDict().get<scalar>("maxAlphaCo");
        const scalar Co = cfl(runTime.deltaTValue(), false).transport;
        return min(nMax, max(label(1), label(std::ceil(Co/maxAlphaCo - 1e-6))));
    }

    const label nSub = dict.getOrDefault<label>("nAlphaSubCycles", 1);
    if (nSub < 1)
    {
        granularInput::invalid(dict, "nAlphaSubCycles", nSub, ">= 1");
    }
    return nSub;
}


void Foam::granularMixture::solve()
{
    const Time& runTime = mesh_.time();
    const label nSub = nAlphaSubCycles();
    if (maxAlphaSubCycles())
    {
        Info<< "Phase transport: " << nSub << " sub-cycles" << endl;
    }

    if (nSub > 1)
    {
        surfaceScalarField rhoPhiSum
        (
            IOobject("rhoPhiSum", runTime.timeName(), mesh_),
            mesh_,
            dimensionedScalar(rhoPhi_.dimensions(), Zero)
        );
        PtrList<surfaceScalarField> alphaPhiSums(alphas_.size());
        forAll(alphaPhiSums, i)
        {
            alphaPhiSums.set
            (
                i,
                new surfaceScalarField
                (
                    IOobject("alphaPhiSum" + Foam::name(i), runTime.timeName(), mesh_),
                    mesh_,
                    dimensionedScalar(alphaPhis_[i].dimensions(), Zero)
                )
            );
        }
        const dimensionedScalar totalDeltaT = runTime.deltaT();

        for
        (
            subCycle<volScalarField> alphaSubCycle(alphas_[0], nSub);
            !(++alphaSubCycle).end();
        )
        {
            solveAlphas();
            rhoPhiSum += (runTime.deltaT()/totalDeltaT)*rhoPhi_;
            forAll(alphaPhiSums, i)
            {
                alphaPhiSums[i] += (runTime.deltaT()/totalDeltaT)*alphaPhis_[i];
            }
        }
        rhoPhi_ = rhoPhiSum;
        forAll(alphaPhiSums, i)
        {
            alphaPhis_[i] = alphaPhiSums[i];
        }
    }
    else
    {
        solveAlphas();
    }

    // One line per phase: volume, min, max
    scalarField sumAlpha(mesh_.nCells(), Zero);
    for (const volScalarField& alpha : alphas_)
    {
        Info<< "    " << alpha.name() << " volume = "
            << gSum(mesh_.V().field()*alpha.primitiveField())
            << " min = " << gMin(alpha.primitiveField())
            << " max = " << gMax(alpha.primitiveField()) << nl;
        sumAlpha += alpha.primitiveField();
    }
    Info<< "    sum of phase fractions: min = " << gMin(sumAlpha)
        << " max = " << gMax(sumAlpha) << endl;

    calcMixture();
}


bool Foam::granularMixture::read()
{
    if (regIOobject::read())
    {
        // Everything again, with the checks of the start; the phases,
        // whose fields are read at the start only, cannot change
        const word airName(airName_);
        readAir();
        if (airName_ != airName)
        {
            const dictionary& dict = subDict("air");
            FatalIOErrorInFunction(dict)
                << "Invalid value of keyword 'name' in dictionary "
                << dict.name() << ": name = " << airName_ << " changed"
                << " during the run (it was " << airName << "): the phase"
                << " fields are read at the start only; stop the run and"
                << " start it again" << nl
                << exit(FatalIOError);
        }
        tensionWarning_ = readTensionWarning();
        rheology_.read(*this);
        segregation_.read(*this, "segregation", rheology_);
        diffusion_.read(*this, "diffusion", rheology_);

        Info<< "Re-read " << objectPath() << ": the air, the rheology,"
            << " the segregation and the diffusion laws" << nl << endl;
        return true;
    }
    return false;
}


// ************************************************************************* //
