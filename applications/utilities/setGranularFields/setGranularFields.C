/*---------------------------------------------------------------------------*\
    granularSegregationFoam: coupled mu(I) rheology and size segregation
    Copyright (C) 2026 The granularSegregationFoam authors
    License: GNU General Public License v3 or later (see LICENSE)

Application
    setGranularFields

Group
    grpPreProcessingUtilities

Description
    Sets the initial state of a granular case: grains of a given composition
    below a plane, air above, and a velocity that is either uniform or the
    solid-body rotation of the case's mesh, as in the square drum (7.1),
    (7.2) of Barker et al. (2021):

        (phi^a, phi^nu) = (0, c^nu)   below the plane
                        = (1, 0)      above it
        u_0 = Omega a x (x - x_0)     (rotation of constant/dynamicMeshDict)

    A cell cut by the plane gets the exact fraction of its volume below it
    (the cell is decomposed into tetrahedra that are sliced by the plane),
    so the grain volume is the volume below the plane whatever the mesh.

    The fields alpha.<phase> of every phase of constant/granularProperties
    and U must exist in the start time (from 0.orig): only their internal
    values are set, their boundary conditions are kept, as setFields does.

Usage
    system/setGranularFieldsDict:
    \verbatim
    grains
    {
        point       (0 0.04 0);     // a point of the plane
        normal      (0 1 0);        // from the grains into the air
        fractions   { small 0.5; large 0.5; }   // of the grains, sum 1
    }
    velocity        rotation;       // (7.2); or a vector, e.g. (0 0 0)
    \endverbatim

\*---------------------------------------------------------------------------*/

#include "fvCFD.H"
#include "meshRotation.H"
#include "granularInput.H"
#include "plane.H"

// * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * //

namespace
{
    using namespace Foam;

    //- |volume| of the tetrahedron (a, b, c, d)
    scalar tetVolume(const point& a, const point& b, const point& c, const point& d)
    {
        return mag((b - a) & ((c - a) ^ (d - a)))/6;
    }

    //- Volume of the tetrahedron p on the side d < 0 of a plane, d the
    //  signed distances of its vertices (points on the plane, d = 0, are
    //  not below, so no division by zero)
    scalar volumeBelow(const FixedList<point, 4>& p, const FixedList<scalar, 4>& d)
    {
        // Where the edge (i, j) crosses the plane, d[i] < 0 <= d[j]
        const auto cut = [&](label i, label j)
        {
            return p[i] + d[i]/(d[i] - d[j])*(p[j] - p[i]);
        };

        labelList below;
        labelList above;
        forAll(d, i)
        {
            (d[i] < 0 ? below : above).append(i);
        }

        const scalar V = tetVolume(p[0], p[1], p[2], p[3]);
        switch (below.size())
        {
            case 0:
                return 0;
            case 4:
                return V;
            case 1:
            {
                const label i = below[0];
                return tetVolume
                (
                    p[i], cut(i, above[0]), cut(i, above[1]), cut(i, above[2])
                );
            }
            case 3:
            {
                // V minus the corner above; d = 0 there leaves no corner
                const label k = above[0];
                if (d[k] <= 0)
                {
                    return V;
                }
                const auto cutAbove = [&](label j)
                {
                    return p[k] + d[k]/(d[k] - d[j])*(p[j] - p[k]);
                };
                return V - tetVolume
                (
                    p[k], cutAbove(below[0]), cutAbove(below[1]),
                    cutAbove(below[2])
                );
            }
            default:
            {
                // A wedge: the triangles (a, ac, ad) and (b, bc, bd),
                // split into three tetrahedra
                const label a = below[0], b = below[1];
                const label c = above[0], e = above[1];
                const point A0(p[a]), A1(cut(a, c)), A2(cut(a, e));
                const point B0(p[b]), B1(cut(b, c)), B2(cut(b, e));
                return
                    tetVolume(A0, A1, A2, B2)
                  + tetVolume(A0, A1, B1, B2)
                  + tetVolume(A0, B0, B1, B2);
            }
        }
    }

    //- Fraction of each cell's volume on the side of the plane opposite to
    //  its normal, exact for polyhedral cells (decomposed into tetrahedra
    //  about the cell centre and the face centres)
    scalarField fractionBelow(const fvMesh& mesh, const plane& pl)
    {
        const pointField& pts = mesh.points();
        const pointField& fc = mesh.faceCentres();
        const pointField& cc = mesh.cellCentres();
        const faceList& faces = mesh.faces();

        scalarField below(mesh.nCells());
        forAll(below, celli)
        {
            scalar vBelow = 0;
            scalar vAll = 0;
            for (const label facei : mesh.cells()[celli])
            {
                const face& f = faces[facei];
                forAll(f, fp)
                {
                    const FixedList<point, 4> tet
                    ({
                        cc[celli], fc[facei], pts[f[fp]], pts[f.nextLabel(fp)]
                    });
                    FixedList<scalar, 4> d;
                    forAll(tet, i)
                    {
                        d[i] = pl.signedDistance(tet[i]);
                    }
                    vBelow += volumeBelow(tet, d);
                    vAll += tetVolume(tet[0], tet[1], tet[2], tet[3]);
                }
            }
            below[celli] = vBelow/vAll;
        }
        return below;
    }

    //- The fractions of the grain phases below the plane, in the order of
    //  grainNames, checked: each in [0, 1], their sum 1, every name a grain
    //  phase of granularProperties
    scalarList readFractions
    (
        const dictionary& fracDict,
        const wordList& grainNames,
        const fileName& propertiesName
    )
    {
        for (const word& key : fracDict.toc())
        {
            if (!grainNames.found(key))
            {
                FatalIOErrorInFunction(fracDict)
                    << "Phase " << key << " in " << fracDict.name()
                    << " is not a grain phase of " << propertiesName
                    << "; the grain phases are " << grainNames << nl
                    << exit(FatalIOError);
            }
        }
        scalarList c(grainNames.size());
        scalar sumC = 0;
        forAll(grainNames, i)
        {
            c[i] = granularInput::readNonNegative
            (
                fracDict, grainNames[i]
            ).value();
            if (c[i] > 1)
            {
                granularInput::invalid
                (
                    fracDict, grainNames[i], c[i], "a fraction lies in [0, 1]"
                );
            }
            sumC += c[i];
        }
        if (mag(sumC - 1) > 1e-12)
        {
            FatalIOErrorInFunction(fracDict)
                << "The fractions in " << fracDict.name() << " sum to "
                << sumC << ", not 1" << nl << exit(FatalIOError);
        }
        return c;
    }

    //- alpha.<phase> of the start time with the internal values given,
    //  its boundary conditions kept (not written)
    volScalarField* alphaField
    (
        const fvMesh& mesh,
        const word& phase,
        const scalarField& value
    )
    {
        auto* alphaPtr = new volScalarField
        (
            IOobject
            (
                IOobject::groupName("alpha", phase),
                mesh.time().timeName(),
                mesh,
                IOobject::MUST_READ,
                IOobject::NO_WRITE
            ),
            mesh
        );
        alphaPtr->primitiveFieldRef() = value;
        alphaPtr->correctBoundaryConditions();
        Info<< "    " << alphaPtr->name() << ": volume "
            << gSum(mesh.V().field()*value) << " m^3" << endl;
        return alphaPtr;
    }

    //- The plane of grainsDict (point, normal), the normal not zero
    plane readPlane(const dictionary& grainsDict)
    {
        const point p0(grainsDict.get<point>("point"));
        const vector n(grainsDict.get<vector>("normal"));
        if (mag(n) < SMALL)
        {
            FatalIOErrorInFunction(grainsDict)
                << "normal = " << n << " in " << grainsDict.name()
                << ": the normal of the plane must not be zero" << nl
                << exit(FatalIOError);
        }
        return plane(p0, n);
    }

    //- Air above the plane, the grains' composition c below it (not
    //  written)
    PtrList<volScalarField> phaseFields
    (
        const fvMesh& mesh,
        const word& airName,
        const wordList& grainNames,
        const scalarList& c,
        const scalarField& below
    )
    {
        // A zero volume flux, as at rest, for the boundary conditions that
        // look up phi when evaluated (inletOutlet: zero gradient at zero
        // flux)
        const surfaceScalarField phi
        (
            IOobject
            (
                "phi",
                mesh.time().timeName(),
                mesh,
                IOobject::NO_READ,
                IOobject::NO_WRITE
            ),
            mesh,
            dimensionedScalar(dimVolume/dimTime, Zero)
        );

        PtrList<volScalarField> alphas(grainNames.size() + 1);
        alphas.set(0, alphaField(mesh, airName, 1 - below));
        forAll(grainNames, i)
        {
            alphas.set(i + 1, alphaField(mesh, grainNames[i], c[i]*below));
        }
        return alphas;
    }

    //- U of the start time: the mesh's solid-body rotation (7.2) when
    //  velocity is "rotation", u0 otherwise (not written)
    tmp<volVectorField> velocityField
    (
        const fvMesh& mesh,
        const word& velocity,
        const vector& u0
    )
    {
        const Time& runTime = mesh.time();
        tmp<volVectorField> tU
        (
            new volVectorField
            (
                IOobject
                (
                    "U",
                    runTime.timeName(),
                    mesh,
                    IOobject::MUST_READ,
                    IOobject::NO_WRITE
                ),
                mesh
            )
        );
        volVectorField& U = tU.ref();
        if (velocity == "rotation")
        {
            const meshRotation rotation(runTime);
            U.primitiveFieldRef() =
                rotation.velocity(mesh.C().primitiveField(), runTime.value());
            Info<< "U: the rotation " << rotation.omega(runTime.value())
                << " rad/s about " << rotation.axis() << " through "
                << rotation.origin() << endl;
        }
        else
        {
            U.primitiveFieldRef() = u0;
            Info<< "U: uniform " << u0 << endl;
        }
        U.correctBoundaryConditions();
        return tU;
    }
}


int main(int argc, char *argv[])
{
    argList::addNote
    (
        "Set the initial grains, air and velocity of a granular case from"
        " system/setGranularFieldsDict (the square drum's (7.1)-(7.2))."
    );

    #include "addRegionOption.H"
    #include "setRootCase.H"
    #include "createTime.H"
    #include "createNamedMesh.H"

    const IOdictionary setDict
    (
        IOobject
        (
            "setGranularFieldsDict",
            runTime.system(),
            mesh,
            IOobject::MUST_READ,
            IOobject::NO_WRITE
        )
    );

    const IOdictionary properties
    (
        IOobject
        (
            "granularProperties",
            runTime.constant(),
            mesh,
            IOobject::MUST_READ,
            IOobject::NO_WRITE,
            false
        )
    );
    const word airName
    (
        properties.subDict("air").getOrDefault<word>("name", "air")
    );
    const wordList grainNames(properties.subDict("grains").toc());

    const dictionary& grainsDict = setDict.subDict("grains");
    const plane grainSurface(readPlane(grainsDict));
    const scalarList c
    (
        readFractions
        (
            grainsDict.subDict("fractions"), grainNames, properties.name()
        )
    );
    vector u0(Zero);
    const word velocity
    (
        granularInput::readVectorOrWord(setDict, "velocity", {"rotation"}, u0)
    );

    Info<< "Grains below the plane through " << grainSurface.origin()
        << " with normal " << grainSurface.normal() << nl;
    const PtrList<volScalarField> alphas
    (
        phaseFields
        (
            mesh, airName, grainNames, c, fractionBelow(mesh, grainSurface)
        )
    );
    const tmp<volVectorField> U(velocityField(mesh, velocity, u0));

    // Written once every field is set: bad input writes nothing
    for (const volScalarField& alpha : alphas)
    {
        alpha.write();
    }
    U().write();

    Info<< "\nEnd\n" << endl;

    return 0;
}


// ************************************************************************* //
