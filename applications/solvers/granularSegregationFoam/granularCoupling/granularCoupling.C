/*---------------------------------------------------------------------------*\
    granularSegregationFoam: coupled mu(I) rheology and size segregation
    Copyright (C) 2026 The granularSegregationFoam authors
    License: GNU General Public License v3 or later (see LICENSE)
\*---------------------------------------------------------------------------*/

#include "granularCoupling.H"
#include "fvMatrices.H"
#include "fvm.H"
#include "fvc.H"
#include "extrapolatedCalculatedFvPatchFields.H"
#include "granularInput.H"
#include "adjustPhi.H"

// * * * * * * * * * * * * * * * Static Data * * * * * * * * * * * * * * * * //

const Foam::Enum<Foam::granularCoupling::pressureCoupling>
Foam::granularCoupling::pressureCouplingNames
({
    { pressureCoupling::PISO, "PISO" },
    { pressureCoupling::SIMPLEC, "SIMPLEC" },
    { pressureCoupling::Krylov, "Krylov" },
});


const Foam::Enum<Foam::granularCoupling::transposeStress>
Foam::granularCoupling::transposeStressNames
({
    { transposeStress::full, "full" },
    { transposeStress::gradEta, "gradEta" },
    { transposeStress::none, "none" },
});


const Foam::Enum<Foam::granularCoupling::viscousStress>
Foam::granularCoupling::viscousStressNames
({
    { viscousStress::explicitStress, "explicit" },
    { viscousStress::implicitStress, "implicit" },
});


const Foam::Enum<Foam::granularCoupling::startPressure>
Foam::granularCoupling::startPressureNames
({
    { startPressure::p, "p" },
    { startPressure::p_rgh, "p_rgh" },
});


// * * * * * * * * * * * * * * * * Constructors  * * * * * * * * * * * * * * //

Foam::granularCoupling::granularCoupling(const pimpleControl& pimple)
:
    pimple_(pimple),
    coupling_(pressureCoupling::PISO),
    transpose_(transposeStress::full),
    start_(startPressure::p_rgh),
    tolerance_(0),
    nRheologyCorrectors_(0),
    corr_(0),
    final_(false),
    nextFinal_(false),
    nSolutions_(0),
    residual_(0)
{
    read();
    Info<< "Pressure coupling: " << pressureCouplingNames[coupling_];
    if (Krylov())
    {
        Info<< " (FGMRES on U and p_rgh), then one PISO corrector";
    }
    else
    {
        Info<< ", at most " << pimple_.nCorrPISO() << " correctors";
    }
    if (tolerance_ > 0 && !Krylov())
    {
        Info<< ", ended once the initial residual of p_rgh is below "
            << tolerance_;
    }
    Info<< "; transpose stress " << transposeStressNames[transpose_]
        << "; each step starts from the last "
        << startPressureNames[start_] << nl << endl;

    // Too few PISO correctors for the implicit stress (class description)
    const bool implicitStress =
        granularInput::readEnum
        (
            pimple_.dict(), "viscousStress",
            viscousStressNames, viscousStress::explicitStress
        )
     == viscousStress::implicitStress;
    if (implicitStress && !Krylov() && pimple_.nCorrPISO() < 4)
    {
        WarningInFunction
            << "viscousStress implicit with nCorrectors "
            << pimple_.nCorrPISO() << " in " << pimple_.dict().name()
            << ": the pressure may not converge within a step at large"
            << " Delta t; the chute tutorial uses nCorrectors 10" << endl;
    }

    if (pimple_.nCorrPIMPLE() > 1)
    {
        WarningInFunction
            << "nOuterCorrectors " << pimple_.nCorrPIMPLE() << " in "
            << pimple_.dict().name() << ": outer iterations diverged on the"
            << " chute, the square drum and the periodic layer with the"
            << " implicit stress (1 is the tested setting)" << endl;
    }
}


// * * * * * * * * * * * * * * * Member Functions  * * * * * * * * * * * * * //

Foam::granularCoupling::viscousStress
Foam::granularCoupling::readViscousStress(const pimpleControl& pimple)
{
    const dictionary& dict = pimple.dict();
    const viscousStress v = granularInput::readEnum
    (
        dict, "viscousStress",
        viscousStressNames, viscousStress::explicitStress
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


void Foam::granularCoupling::read()
{
    const dictionary& dict = pimple_.dict();

    coupling_ = granularInput::readEnum
    (
        dict, "pressureCoupling", pressureCouplingNames, pressureCoupling::PISO
    );

    transpose_ = granularInput::readEnum
    (
        dict, "transposeStress", transposeStressNames, transposeStress::full
    );

    start_ = granularInput::readEnum
    (
        dict, "startPressure", startPressureNames, startPressure::p_rgh
    );

    const label nCorr = dict.getOrDefault<label>("nCorrectors", 1);
    if (nCorr < 1)
    {
        granularInput::invalid(dict, "nCorrectors", nCorr, ">= 1");
    }

    nRheologyCorrectors_ =
        dict.getOrDefault<label>("nRheologyCorrectors", 0);
    if (nRheologyCorrectors_ < 0)
    {
        granularInput::invalid
        (
            dict, "nRheologyCorrectors", nRheologyCorrectors_, ">= 0"
        );
    }

    tolerance_ = dict.getOrDefault<scalar>("pRghTolerance", 0);
    if (tolerance_ < 0 || tolerance_ >= 1)
    {
        granularInput::invalid
        (
            dict, "pRghTolerance", tolerance_,
            "0 <= pRghTolerance < 1; 0: run every corrector"
        );
    }
}


void Foam::granularCoupling::keepPressure
(
    volScalarField& p_rgh,
    const volScalarField& rho,
    const scalarField& rho0,
    const volScalarField& gh
) const
{
    if (start_ == startPressure::p)
    {
        p_rgh.primitiveFieldRef() -=
            (rho.primitiveField() - rho0)*gh.primitiveField();
    }
}


Foam::tmp<Foam::fvVectorMatrix> Foam::granularCoupling::divStress
(
    const incompressible::turbulenceModel& turbulence,
    const volScalarField& rho,
    volVectorField& U
) const
{
    if (transpose_ == transposeStress::full)
    {
        return turbulence.divDevRhoReff(rho, U);
    }

    const volScalarField eta("etaEff", rho*turbulence.nuEff());
    tmp<fvVectorMatrix> tEqn(-fvm::laplacian(eta, U));
    if (transpose_ == transposeStress::gradEta)
    {
        tEqn.ref() -= fvc::grad(U) & fvc::grad(eta);
    }
    return tEqn;
}


Foam::tmp<Foam::volScalarField> Foam::granularCoupling::followingH1
(
    const fvVectorMatrix& UEqn,
    const volScalarField& rho
)
{
    const fvMesh& mesh = rho.mesh();

    // With the dimensions and patches of fvMatrix::H1
    tmp<volScalarField> tH1
    (
        volScalarField::New
        (
            "H(1)",
            mesh,
            dimensionedScalar
            (
                UEqn.dimensions()/(dimVol*UEqn.psi().dimensions()),
                Zero
            ),
            extrapolatedCalculatedFvPatchScalarField::typeName
        )
    );
    scalarField& H1 = tH1.ref().primitiveFieldRef();

    const labelUList& own = mesh.owner();
    const labelUList& nei = mesh.neighbour();
    const scalarField& lower = UEqn.lower();
    const scalarField& upper = UEqn.upper();

    forAll(own, facei)
    {
        const label o = own[facei];
        const label n = nei[facei];
        H1[n] -= lower[facei]*min(scalar(1), rho[n]/rho[o]);
        H1[o] -= upper[facei]*min(scalar(1), rho[o]/rho[n]);
    }

    // Processor and cyclic neighbours, with fvMatrix::H1's coefficient
    forAll(rho.boundaryField(), patchi)
    {
        const fvPatchScalarField& rhop = rho.boundaryField()[patchi];
        if (!rhop.coupled() || rhop.empty())
        {
            continue;
        }
        const scalarField rhoN(rhop.patchNeighbourField());
        const scalarField a(UEqn.boundaryCoeffs()[patchi].component(0));
        const labelUList& cells = mesh.boundary()[patchi].faceCells();
        forAll(cells, i)
        {
            H1[cells[i]] += a[i]*min(scalar(1), rho[cells[i]]/rhoN[i]);
        }
    }

    H1 /= mesh.V();
    tH1.ref().correctBoundaryConditions();

    return tH1;
}


Foam::tmp<Foam::volScalarField> Foam::granularCoupling::pressureCoefficient
(
    const fvVectorMatrix& UEqn,
    const volScalarField& rAU,
    const volScalarField& rho
)
{
    return tmp<volScalarField>::New
    (
        "rAtU",
        1.0/max(1.0/rAU - followingH1(UEqn, rho), rho/rho.time().deltaT())
    );
}


Foam::tmp<Foam::surfaceScalarField> Foam::granularCoupling::fluxHbyA
(
    const volVectorField& HbyA,
    const surfaceScalarField& phiDdtCorr,
    const volVectorField& U,
    volScalarField& p_rgh,
    const IOMRFZoneList& MRF
)
{
    tmp<surfaceScalarField> tphiHbyA
    (
        new surfaceScalarField("phiHbyA", fvc::flux(HbyA) + phiDdtCorr)
    );
    surfaceScalarField& phiHbyA = tphiHbyA.ref();
    MRF.makeRelative(phiHbyA);

    if (p_rgh.needReference())
    {
        fvc::makeRelative(phiHbyA, U);
        adjustPhi(phiHbyA, U, p_rgh);
        fvc::makeAbsolute(phiHbyA, U);
    }
    return tphiHbyA;
}


void Foam::granularCoupling::newTimeStep()
{
    nSolutions_ = 0;
    residual_ = 0;
}


bool Foam::granularCoupling::correct()
{
    if (final_)
    {
        // The final corrector was solved: the loop of this outer iteration
        // is done; the next outer iteration starts again
        corr_ = 0;
        final_ = false;
        nextFinal_ = false;
        return false;
    }

    ++corr_;
    final_ = nextFinal_ || Krylov() || corr_ >= pimple_.nCorrPISO();
    return true;
}


void Foam::granularCoupling::store
(
    const scalar initialResidual,
    const bool firstOfCorrector
)
{
    ++nSolutions_;
    if (!firstOfCorrector)
    {
        return;
    }
    residual_ = initialResidual;
    if (tolerance_ > 0 && initialResidual < tolerance_)
    {
        nextFinal_ = true;
    }
}


void Foam::granularCoupling::report() const
{
    Info<< "Pressure coupling: " << nSolutions_ << " pressure solutions,"
        << " initial residual of the last " << residual_;
    if (tolerance_ > 0 && residual_ >= tolerance_)
    {
        Info<< ": not converged to pRghTolerance " << tolerance_
            << " within nCorrectors " << pimple_.nCorrPISO();
    }
    Info<< endl;
}


// ************************************************************************* //
