/*---------------------------------------------------------------------------*\
    granularSegregationFoam: coupled mu(I) rheology and size segregation
    Copyright (C) 2026 The granularSegregationFoam authors
    License: GNU General Public License v3 or later (see LICENSE)

Application
    Test-granularMixture

Description
    Checks of the parts of libgranularMixture on the case it runs in (a
    case with U, p_rgh and the phase fractions, e.g. the segregationColumn
    tutorial after blockMesh and setGranularFields), with U and p set here:

    - granularGravity: g = hydrostatic() + bodyForce(), g_b along the
      cyclic direction;
    - granularPhases: the fractions sum to 1, the segregation index is in
      [0, 1];
    - granularPairFluxes: the pairwise fluxes sum to zero over the phases
      (2.12) and vanish on the walls (2.17);
    - granularTransport: one step of the mixture (solve()) keeps every
      phase's volume and [0, 1];
    - granularTimeStep: with U = 0 the convective part is 0, the viscous
      part is max(nu G) dt, G = 1/dz^2 + 1/dx^2 inside a uniform column
      cyclic in x;
    - granularPressure: for p = rho^a g.x + c, airLevel(p) = c and level()
      takes it to pRefValue.

    Prints "PASS <check>" or "FAIL <check>" for each, then
    "N passed, M failed"; exits with the number failed.

\*---------------------------------------------------------------------------*/

#include "fvCFD.H"
#include "granularMixture.H"

// * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * //

namespace
{
    Foam::label nPassed = 0;
    Foam::label nFailed = 0;

    //- PASS when the measured value is at most tol
    void check(const char* what, const Foam::scalar value, const Foam::scalar tol)
    {
        using namespace Foam;
        const bool ok = value <= tol;
        Info<< (ok ? "PASS " : "FAIL ") << what << ": " << value
            << " (tolerance " << tol << ")" << endl;
        ++(ok ? nPassed : nFailed);
    }

    //- Sum of V alpha
    Foam::scalar volume(const Foam::volScalarField& alpha)
    {
        return Foam::gSum(alpha.mesh().V().field()*alpha.primitiveField());
    }

    //- g = hydrostatic() + bodyForce(), g_b along the cyclic direction
    void checkGravity(const fvMesh& mesh, const granularMixture& mixture)
    {
        const granularGravity gravity(mesh, mixture);
        const vector g(gravity.g().value());
        check
        (
            "granularGravity: |g - hydrostatic - bodyForce|/|g|",
            mag(g - gravity.hydrostatic().value() - gravity.bodyForce())
           /mag(g),
            1e-15
        );
        check
        (
            "granularGravity: the body force of a cyclic case is not zero,"
            " 1 - |g_b|/|g.x| (x the cyclic direction)",
            mag(1 - mag(gravity.bodyForce())/max(mag(g.x()), VSMALL)),
            1e-12
        );
    }

    //- The fractions sum to 1, the index is in [0, 1], the air is phase 0
    void checkPhases(const fvMesh& mesh, const granularPhases& phases)
    {
        scalarField sum(mesh.nCells(), Zero);
        for (const volScalarField& alpha : phases.alphas())
        {
            sum += alpha.primitiveField();
        }
        check
        (
            "granularPhases: max |sum of fractions - 1|",
            gMax(mag(sum - 1)()), 1e-12
        );
        const scalar S = phases.segregationIndex();
        check
        (
            "granularPhases: segregation index outside [0, 1] by",
            max(-S, S - 1), 0
        );
        const label top = findMax(mesh.C().component(2)());
        check
        (
            "granularPhases: the air is phase 0, 1 - its fraction at the top",
            mag(1 - phases.air().primitiveField()[top]),
            1e-12
        );
    }

    //- The pairwise fluxes of the mixture's current rheology: the largest
    //  |F|, the largest |sum over the phases of F| and the largest |F| on
    //  the uncoupled patches
    FixedList<scalar, 3> pairFluxBounds
    (
        const fvMesh& mesh,
        const granularMixture& mixture,
        const surfaceScalarField& phi
    )
    {
        const PtrList<volScalarField>& alphas = mixture.phases().alphas();
        PtrList<surfaceScalarField> alphaPhis(alphas.size());
        PtrList<surfaceScalarField> relPhis(alphas.size());
        forAll(alphas, i)
        {
            alphaPhis.set(i, new surfaceScalarField("a" + name(i), 0*phi));
            relPhis.set(i, new surfaceScalarField("r" + name(i), alphaPhis[i]));
        }
        // The pairs of the mixture, as the transport builds them
        List<labelPair> pairs;
        PtrList<surfaceScalarField> phirs;
        granularAir air(mixture, granularGravity(mesh, mixture));
        granularPairFluxes pairFluxes(mesh, mixture, mixture.rheology());
        PtrList<scalarField> w;
        mixture.phases().grainFractions(w);
        UPtrList<const scalarField> wc(w.size());
        forAll(w, k)
        {
            wc.set(k, &w[k]);
        }
        const auto field = [&](const word& name) -> const scalarField&
        {
            return mesh.lookupObject<volScalarField>(name).primitiveField();
        };
        pairFluxes.correct
        (
            granularState
            {
                field("shearRate"), field("pGranular"), field("dbar"), wc,
                mag(mixture.gHydrostatic().value())
            }
        );
        pairFluxes.relativeFluxes
        (
            alphas, vector(0, 0, -1), air, phi, pairs, phirs
        );
        pairFluxes.add(alphas, pairs, phirs, alphaPhis, &relPhis);

        FixedList<scalar, 3> bounds(Zero);
        surfaceScalarField total(0*relPhis[0]);
        for (const surfaceScalarField& F : relPhis)
        {
            total += F;
            bounds[0] = max(bounds[0], gMax(mag(F.primitiveField())()));
            for (const fvsPatchScalarField& Fp : F.boundaryField())
            {
                if (!Fp.coupled() && Fp.size())
                {
                    bounds[2] = max(bounds[2], gMax(mag(Fp)()));
                }
            }
        }
        bounds[1] = gMax(mag(total.primitiveField())());
        return bounds;
    }

    //- (2.12) and (2.17) for the pairwise fluxes
    void checkPairFluxes
    (
        const fvMesh& mesh,
        const granularMixture& mixture,
        const surfaceScalarField& phi
    )
    {
        const FixedList<scalar, 3> b(pairFluxBounds(mesh, mixture, phi));
        check
        (
            "granularPairFluxes: relative fluxes exist, 1 - sign(max |F|)",
            1 - sign(b[0] - VSMALL), 0
        );
        check
        (
            "granularPairFluxes: (2.12) max |sum F|/max |F|",
            b[1]/max(b[0], VSMALL), 1e-14
        );
        check
        (
            "granularPairFluxes: (2.17) max |F| on uncoupled patches",
            b[2], 0
        );
    }

    //- With U = 0: the convective part is 0, the viscous part max(nu G) dt,
    //  G = 1/dz^2 + 1/dx^2 inside a uniform column cyclic in x
    void checkTimeStep
    (
        const fvMesh& mesh,
        granularMixture& mixture,
        volVectorField& U,
        surfaceScalarField& phi
    )
    {
        U = dimensionedVector(dimVelocity, Zero);
        U.correctBoundaryConditions();
        phi = fvc::flux(U);
        const scalar dt = mesh.time().deltaTValue();
        const granularMixture::cflParts parts = mixture.cfl(dt, true);
        check
        (
            "granularTimeStep: convective part with U = 0",
            parts.convective, 0
        );

        granularTimeStep timeStep(mesh);
        const scalarField& G = timeStep.G();
        const scalar dzInv = gMax(mesh.deltaCoeffs().primitiveField());
        scalar dxInv = 0;
        forAll(mesh.boundary(), patchi)
        {
            if (mesh.boundary()[patchi].coupled())
            {
                dxInv = max
                (
                    dxInv, gMax(mesh.deltaCoeffs().boundaryField()[patchi])
                );
            }
        }
        const label mid = mesh.nCells()/2;
        check
        (
            "granularTimeStep: |G/(1/dz^2 + 1/dx^2) - 1| inside a uniform"
            " column",
            mag(G[mid]/(sqr(dzInv) + sqr(dxInv)) - 1), 1e-12
        );
        const scalar nuG = gMax(mixture.nu()().primitiveField()*G);
        check
        (
            "granularTimeStep: |viscous part - max(nu G) dt|/viscous part",
            mag(parts.viscous - nuG*dt)/parts.viscous,
            1e-14
        );
    }

    //- One step of the mixture keeps every phase's volume and [0, 1]
    void checkTransport
    (
        Time& runTime,
        granularMixture& mixture,
        volVectorField& U,
        surfaceScalarField& phi,
        const volScalarField& p
    )
    {
        const granularPhases& phases = mixture.phases();
        const scalar V = gSum(U.mesh().V().field());
        runTime.setDeltaT(1e-4);
        ++runTime;
        List<scalar> before(phases.size());
        forAll(before, i)
        {
            before[i] = volume(phases[i]);
            const_cast<volScalarField&>(phases[i]).oldTime();
        }
        U = dimensionedVector("u", dimVelocity, vector(0.1, 0, 0));
        phi = fvc::flux(U);
        mixture.correctRheology(p, false);
        mixture.solve();
        scalar drift = 0;
        scalar outside = 0;
        forAll(before, i)
        {
            const scalarField& a = phases[i].primitiveField();
            drift = max(drift, mag(volume(phases[i]) - before[i])/V);
            outside = max(outside, max(-gMin(a), gMax(a) - 1));
        }
        check
        (
            "granularTransport: relative volume change of a phase in one step",
            drift, 1e-12
        );
        check("granularTransport: fractions outside [0, 1] by", outside, 1e-12);
    }

    //- For p = rho^a g.x + c, airLevel(p) = c, and level() takes it to
    //  pRefValue
    void checkPressure
    (
        const fvMesh& mesh,
        const granularMixture& mixture,
        volScalarField& p,
        volScalarField& p_rgh
    )
    {
        const granularAir air(mixture, granularGravity(mesh, mixture));
        const granularGravity gravity(mesh, mixture);
        granularPressure pressure(mixture, mixture.phases(), air, gravity);
        const scalar c = 123.5;
        p.primitiveFieldRef() =
            air.rho().value()
           *(gravity.hydrostatic().value() & mesh.C().primitiveField())
          + c;
        check
        (
            "granularPressure: |airLevel(rho^a g.x + c) - c|/c",
            mag(pressure.airLevel(p) - c)/c, 1e-12
        );
        pressure.level(p, p_rgh, 7);
        check
        (
            "granularPressure: |airLevel after level(7) - 7|/7",
            mag(pressure.airLevel(p) - 7)/7, 1e-12
        );
    }
}


int main(int argc, char *argv[])
{
    argList::noParallel();
    #include "setRootCase.H"
    #include "createTime.H"
    #include "createMesh.H"

    volVectorField U
    (
        IOobject("U", runTime.timeName(), mesh, IOobject::MUST_READ),
        mesh
    );
    U = dimensionedVector(dimVelocity, Zero);
    U.correctBoundaryConditions();
    surfaceScalarField phi("phi", fvc::flux(U));

    granularMixture mixture(U, phi);

    checkGravity(mesh, mixture);
    checkPhases(mesh, mixture.phases());

    // A sheared state, for the rheology, segregation and diffusion
    forAll(U, celli)
    {
        U[celli] = vector(0.5*mesh.C()[celli].z(), 0, 0)/0.01;
    }
    U.correctBoundaryConditions();
    phi = fvc::flux(U);

    volScalarField p
    (
        IOobject("p", runTime.timeName(), mesh),
        mesh,
        dimensionedScalar(dimPressure, Zero)
    );
    volScalarField p_rgh("p_rgh", p);
    const dimensionedVector gH(mixture.gHydrostatic());
    p.primitiveFieldRef() =
        1500*(gH.value() & (mesh.C().primitiveField() - vector(0, 0, 0.01)));
    mixture.correctRheology(p, false);

    checkPairFluxes(mesh, mixture, phi);
    checkTimeStep(mesh, mixture, U, phi);
    checkTransport(runTime, mixture, U, phi, p);
    checkPressure(mesh, mixture, p, p_rgh);

    Info<< nPassed << " passed, " << nFailed << " failed" << endl;
    return nFailed;
}


// ************************************************************************* //
