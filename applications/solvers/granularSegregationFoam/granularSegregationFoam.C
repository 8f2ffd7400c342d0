/*---------------------------------------------------------------------------*\
    granularSegregationFoam: coupled mu(I) rheology and size segregation
    Copyright (C) 2026 The granularSegregationFoam authors
    License: GNU General Public License v3 or later (see LICENSE)

Application
    granularSegregationFoam

Group
    grpMultiphaseSolvers

Description
    Solver for the incompressible mixture of air and any number of grain-size
    phases of Barker, Rauter, Maguire, Johnson & Gray (2021), "Coupling
    rheology and segregation in granular flows", J. Fluid Mech. 909, A22.

    Derived from multiphaseInterFoam (v1912): its PIMPLE loop, dynamic
    meshes and MPI, with a pressure-velocity coupling (4.1)-(4.2) of PISO
    or SIMPLEC correctors, or a Krylov coupling (pressureCoupling.H,
    granularCoupling, UEqn.H, pCoefficients.H, pEqn.H); the phases are
    transported with MULES by granularMixture, with pairwise segregation
    (2.13) and Maxwell-Stefan diffusion (2.15) in the place of interface
    compression, the air segregated out of the grains (4.3)-(4.5), and the
    mu(I) viscosity of libgranularRheology coupled by Picard iteration
    (4.7): every outer corrector re-evaluates the rheology from the latest
    U and p.

    The time step follows the CFL (4.11) with its viscous part, plus the
    segregation and diffusion rates; each part is logged every step.  At
    every write the log shows the volume of every phase and a segregation
    index, and an estimate of the wall time to finish (also once a minute).  With
    fvSolution PIMPLE { momentumPredictor yes; viscousStress implicit; }
    the stress is solved implicitly in the momentum predictor and the
    viscous part no longer limits the step (see granularCoupling.H).

\*---------------------------------------------------------------------------*/

#include "fvCFD.H"
#include "dynamicFvMesh.H"
#include "granularMixture.H"
#include "granularCoupling.H"
#include "granularKrylovCoupling.H"
#include "faceReconstruction.H"
#include "turbulentTransportModel.H"
#include "pimpleControl.H"
#include "fvOptions.H"
#include "CorrectPhi.H"
#include "dynamicMotionSolverFvMesh.H"
#include "solidBodyMotionSolver.H"
#include "meshRotation.H"
#include "landOnWriteTime.H"

// * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * //

int main(int argc, char *argv[])
{
    argList::addNote
    (
        "Solver for an incompressible mixture of air and grain-size phases"
        " with the mu(I)-rheology, size segregation and diffusion"
        " (Barker et al. 2021).\n"
        "With optional mesh motion and mesh topology changes."
    );

    #include "postProcess.H"

    #include "addCheckCaseOptions.H"
    #include "setRootCaseLists.H"
    #include "createTime.H"
    #include "restartTime.H"
    #include "createDynamicFvMesh.H"
    #include "checkMeshMotion.H"
    #include "initContinuityErrs.H"
    #include "createDyMControls.H"
    #include "createFields.H"
    #include "initCorrectPhi.H"
    #include "createUfIfPresent.H"

    granularCoupling coupling(pimple);
    granularKrylovCoupling krylovCoupling(pimple);

    // fvc::reconstruct with the geometry cached (the correctors call it)
    faceReconstruction reconstruct(mesh);

    // fvSolution PIMPLE { viscousStress explicit | implicit; }: does the
    // viscous part of (4.11) limit the time step?
    const bool viscousLimit =
        granularCoupling::readViscousStress(pimple)
     == granularCoupling::viscousStress::explicitStress;

    turbulence->validate();
    mixture.checkFinite(U, p);

    {
        #include "granularCourantNo.H"
        #include "setInitialDeltaT.H"
    }

    const surfaceScalarField& rhoPhi(mixture.rhoPhi());

    #include "createProgress.H"
    mixture.report();
    mixture.reportGrainPressure(p, p_rgh.needReference());

    // * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * //

    Info<< "\nStarting time loop\n" << endl;

    while (runTime.run())
    {
        #include "readDyMControls.H"

        // The time step is set from the state at the start of the step:
        // its rheology and segregation rate, as a restart from the state
        // written here sees them (createFields.H)
        addProfiling(preCFL, "granular::rheologyBeforeCFL");
        mixture.correctRheology(p, p_rgh.needReference());
        mixture.updateSegregationRate();
        endProfiling(preCFL);

        #include "granularCourantNo.H"
        #include "alphaCourantNo.H"
        #include "transportCourantNo.H"
        #include "setGranularDeltaT.H"

        ++runTime;

        Info<< "Time = " << runTime.timeName() << nl << endl;

        coupling.read();
        krylovCoupling.read();
        coupling.newTimeStep();

        // --- Pressure-velocity PIMPLE corrector loop
        while (pimple.loop())
        {
            #include "moveMesh.H"

            // The reconstruction's geometry of the mesh as it now is
            reconstruct.update();

            // Picard: rheology of the previous iterate (at the first
            // iteration of a fixed mesh, the one computed before the time
            // step from the same fields), then the phases
            if (!pimple.firstIter() || mesh.changing())
            {
                mixture.correctRheology(p, p_rgh.needReference());
            }
            addProfiling(transport, "granular::phases");
            const scalarField rho0(rho.primitiveField());
            mixture.solve();
            rho = mixture.rho();
            coupling.keepPressure(p_rgh, rho, rho0, gh);
            endProfiling(transport);

            // The face forces of (4.1) besides the pressure gradient:
            // surface tension and buoyancy
            const surfaceScalarField faceForce
            (
                "faceForce",
                mixture.surfaceTensionForce() - ghf*fvc::snGrad(rho)
            );

            // The momentum equation and the pressure coupling, then as many
            // passes again as nRheologyCorrectors says, each with the
            // rheology of the last (the phases kept)
            for (label rheologyCorr = 0; ; ++rheologyCorr)
            {
                const bool lastPass =
                    rheologyCorr >= coupling.nRheologyCorrectors();

                // A later pass of the Krylov coupling starts from the last
                // pass's velocity, closer to its solution than a momentum
                // predictor with the last pass's pressure: no predictor
                const bool momentumPredictor =
                    pimple.momentumPredictor()
                 && (rheologyCorr == 0 || !coupling.Krylov());

                addProfiling(momentum, "granular::UEqn");
                #include "UEqn.H"
                endProfiling(momentum);

                #include "pressureCoupling.H"

                if (!correctPhi)
                {
                    rAU.clear();
                }

                // Closed domains: p levelled on the air (p - rho^a g.x =
                // pRefValue on average over it)
                if (p_rgh.needReference())
                {
                    mixture.levelPressure(p, p_rgh, pRefValue);
                }

                if (lastPass)
                {
                    break;
                }

                addProfiling(rheology, "granular::rheologyCorrector");
                mixture.correctRheology(p, p_rgh.needReference());
                endProfiling(rheology);
            }
        }

        coupling.report();
        mixture.reportGrainPressure(p, p_rgh.needReference());
        mixture.checkFinite(U, p);

        runTime.write();

        #include "reportProgress.H"

        runTime.printExecutionTime(Info);
    }

    Info<< "End\n" << endl;

    return 0;
}


// ************************************************************************* //
