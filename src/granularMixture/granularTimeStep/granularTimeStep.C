/*---------------------------------------------------------------------------*\
    granularSegregationFoam: coupled mu(I) rheology and size segregation
    Copyright (C) 2026 The granularSegregationFoam authors
    License: GNU General Public License v3 or later (see LICENSE)
\*---------------------------------------------------------------------------*/

#include "granularTimeStep.H"
#include "fvcSurfaceIntegrate.H"

// * * * * * * * * * * * * Private Member Functions  * * * * * * * * * * * * //

void Foam::granularTimeStep::calcG()
{
    surfaceScalarField geom(mesh_.magSf()*mesh_.deltaCoeffs());
    G_ = 0.5*fvc::surfaceSum(geom)().primitiveField()/mesh_.V().field();
}


// * * * * * * * * * * * * * * * * Constructors  * * * * * * * * * * * * * * //

Foam::granularTimeStep::granularTimeStep(const fvMesh& mesh)
:
    mesh_(mesh),
    G_()
{
    calcG();
}


// * * * * * * * * * * * * * * * Member Functions  * * * * * * * * * * * * * //

const Foam::scalarField& Foam::granularTimeStep::G()
{
    if (mesh_.changing())
    {
        calcG();
    }
    return G_;
}


Foam::granularTimeStep::parts Foam::granularTimeStep::cfl
(
    const scalar deltaT,
    const bool viscousLimit,
    const surfaceScalarField& phi,
    const rates& r,
    const label maxSubCycles
)
{
    const scalarField& G = this->G();
    const scalarField conv
    (
        0.5*fvc::surfaceSum(mag(phi))().primitiveField()/mesh_.V().field()
    );
    const scalarField visc(r.nu*G);

    // Sub-cycled transport: the momentum's part alone limits the step here,
    // the transport's part is divided among the sub-cycles
    const scalarField transport(conv + r.segregation + r.diffusion);
    scalarField total(maxSubCycles ? conv : transport);
    if (viscousLimit)
    {
        total += visc;
    }
    const scalar maxTotal = gMax(total);

    parts p;
    p.convective = gMax(conv)*deltaT;
    p.viscous = gMax(visc)*deltaT;
    p.segregation = gMax(r.segregation)*deltaT;
    p.diffusion = gMax(r.diffusion)*deltaT;
    p.total = maxTotal*deltaT;
    p.maxSubCycles = maxSubCycles;
    p.transport = gMax(transport)*deltaT;

    // The largest part in the cell of the largest total (any processor)
    FixedList<scalar, 4> local(Zero);
    if (total.size())
    {
        const label c = findMax(total);
        local =
        {
            conv[c],
            viscousLimit ? visc[c] : 0,
            maxSubCycles ? 0 : r.segregation[c],
            maxSubCycles ? 0 : r.diffusion[c]
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
    p.limiting = partNames[findMax(local)];

    return p;
}


// ************************************************************************* //
