/*---------------------------------------------------------------------------*\
    granularSegregationFoam: coupled mu(I) rheology and size segregation
    Copyright (C) 2026 The granularSegregationFoam authors
    License: GNU General Public License v3 or later (see LICENSE)
-------------------------------------------------------------------------------
Application
    granularMovingFrame

Group
    grpPreProcessingUtilities

Description
    Continue a chute in a frame moving with velocity U_F (section 5.6):
    u_new = u - U_F everywhere.  At the selected times it shifts the
    velocity U and the flux phi, moves every fixed-value velocity condition
    (a no-slip base becomes a fixed value of -U_F) and sets the frame of
    every BagnoldInletVelocity inflow.  Pressure and phase fractions are
    Galilean invariant and are not touched.

    By default U_F is the depth-averaged inflow velocity ubar e_x of (5.16),
    taken from the case's BagnoldInletVelocity inflow; -velocity gives
    another.  Applying it twice adds the two frames, and the inflow records
    the total, so a run always knows its frame.

Usage
    \b granularMovingFrame [OPTIONS]

    Options:
      - \par -velocity '(Ux Uy Uz)'
        Frame velocity to apply instead of the inflow's ubar e_x

      - \par -time T
        The time to transform (default: the latest)

\*---------------------------------------------------------------------------*/

#include "fvCFD.H"
#include "timeSelector.H"
#include "BagnoldInletVelocityFvPatchVectorField.H"
#include "fixedValueFvPatchFields.H"
#include "mixedFvPatchFields.H"

// * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * //

namespace
{
    using namespace Foam;

    //- The patches of U with a BagnoldInletVelocity condition
    labelList inflowPatches(const volVectorField& U)
    {
        labelList inflows;
        forAll(U.boundaryField(), patchi)
        {
            if (isA<BagnoldInletVelocityFvPatchVectorField>
                (U.boundaryField()[patchi]))
            {
                inflows.append(patchi);
            }
        }
        return inflows;
    }

    //- U_F: -velocity, or ubar e_x (5.16) of the first inflow
    vector frameVelocity
    (
        const argList& args,
        const volVectorField& U,
        const labelList& inflows
    )
    {
        vector Uframe(Zero);
        if (args.readIfPresent("velocity", Uframe))
        {
            Info<< "    frame velocity " << Uframe << " (-velocity)" << nl;
            return Uframe;
        }
        if (inflows.empty())
        {
            FatalErrorInFunction
                << "No BagnoldInletVelocity patch in " << U.objectPath()
                << " to take ubar (5.16) from: give -velocity" << nl
                << exit(FatalError);
        }
        const BagnoldFlow& flow =
            refCast<const BagnoldInletVelocityFvPatchVectorField>
            (
                U.boundaryField()[inflows[0]]
            ).flow();
        Uframe = flow.ubar()*flow.downslope();
        Info<< "    frame velocity " << Uframe << " = ubar e_x (5.16)"
            << " of the inflow " << U.mesh().boundary()[inflows[0]].name()
            << nl;
        return Uframe;
    }

    //- The conditions in the new frame: the inflows record the total frame
    //  velocity, a fixed value (a wall, noSlip included) moves at -U_F
    void shiftBoundaries
    (
        volVectorField& U,
        const labelList& inflows,
        const vector& Uframe
    )
    {
        const fvMesh& mesh = U.mesh();
        forAll(U.boundaryField(), patchi)
        {
            fvPatchVectorField& Up = U.boundaryFieldRef()[patchi];
            const word& name = mesh.boundary()[patchi].name();

            if (inflows.found(patchi))
            {
                auto& inflow =
                    refCast<BagnoldInletVelocityFvPatchVectorField>(Up);
                inflow.setFrameVelocity(inflow.frameVelocity() + Uframe);
                Info<< "    " << name << ": inflow frame velocity "
                    << inflow.frameVelocity() << nl;
            }
            else if (Up.fixesValue())
            {
                const vectorField value(Up - Uframe);
                U.boundaryFieldRef().set
                (
                    patchi,
                    new fixedValueFvPatchVectorField
                    (
                        mesh.boundary()[patchi],
                        U
                    )
                );
                U.boundaryFieldRef()[patchi] == value;
                Info<< "    " << name << ": fixedValue, shifted" << nl;
            }
            else if (Up.size() && isA<mixedFvPatchVectorField>(Up))
            {
                WarningInFunction
                    << "Patch " << name << ": the " << Up.type()
                    << " condition's reference value is not shifted" << nl;
            }
        }
        U.correctBoundaryConditions();
    }

    //- The flux, when the run wrote one: phi - U_F.S_f
    void shiftFlux(const fvMesh& mesh, const vector& Uframe)
    {
        IOobject phiHeader
        (
            "phi",
            mesh.time().timeName(),
            mesh,
            IOobject::MUST_READ,
            IOobject::AUTO_WRITE
        );
        if (phiHeader.typeHeaderOk<surfaceScalarField>(true))
        {
            surfaceScalarField phi(phiHeader, mesh);
            phi -=
                (dimensionedVector("Uframe", dimVelocity, Uframe) & mesh.Sf());
            phi.write();
            Info<< "    phi shifted" << nl;
        }
    }
}


int main(int argc, char *argv[])
{
    argList::addNote
    (
        "Shift a chute to a frame moving with the depth-averaged inflow"
        " velocity (5.16), or -velocity"
    );
    timeSelector::addOptions(false, false);
    argList::addOption
    (
        "velocity",
        "vector",
        "frame velocity (default: ubar e_x of the BagnoldInletVelocity inflow)"
    );

    #include "setRootCase.H"
    #include "createTime.H"

    instantList times = timeSelector::selectIfPresent(runTime, args);
    if (!args.found("time") && !args.found("latestTime"))
    {
        times = instantList(1, runTime.times().last());
    }

    #include "createMesh.H"

    for (const instant& t : times)
    {
        runTime.setTime(t, 0);
        Info<< "Time = " << runTime.timeName() << nl;

        volVectorField U
        (
            IOobject
            (
                "U",
                runTime.timeName(),
                mesh,
                IOobject::MUST_READ,
                IOobject::AUTO_WRITE
            ),
            mesh
        );

        const labelList inflows(inflowPatches(U));
        const vector Uframe(frameVelocity(args, U, inflows));

        U.primitiveFieldRef() -= Uframe;
        shiftBoundaries(U, inflows, Uframe);
        shiftFlux(mesh, Uframe);
        U.write();
    }

    Info<< "End" << nl;

    return 0;
}


// ************************************************************************* //
