/*---------------------------------------------------------------------------*\
    granularSegregationFoam: coupled mu(I) rheology and size segregation
    Copyright (C) 2026 The granularSegregationFoam authors
    License: GNU General Public License v3 or later (see LICENSE)
\*---------------------------------------------------------------------------*/

#include "granularPairFluxes.H"
#include "granularAir.H"
#include "localMax.H"
#include "fvcFlux.H"
#include "fvcSnGrad.H"
#include "fvcSurfaceIntegrate.H"
#include "surfaceInterpolate.H"
#include "zeroGradientFvPatchFields.H"

// * * * * * * * * * * * * Private Member Functions  * * * * * * * * * * * * //

Foam::autoPtr<Foam::volScalarField> Foam::granularPairFluxes::pairField
(
    const word& name,
    const dimensionSet& dims
) const
{
    return autoPtr<volScalarField>::New
    (
        IOobject
        (
            name,
            mesh_.time().timeName(),
            mesh_,
            IOobject::NO_READ,
            IOobject::NO_WRITE
        ),
        mesh_,
        dimensionedScalar(dims, Zero),
        zeroGradientFvPatchScalarField::typeName
    );
}


// * * * * * * * * * * * * * * * * Constructors  * * * * * * * * * * * * * * //

Foam::granularPairFluxes::granularPairFluxes
(
    const fvMesh& mesh,
    const dictionary& dict,
    const granularRheology& rheology
)
:
    mesh_(mesh),
    segregation_(dict, "segregation", rheology),
    diffusion_(dict, "diffusion", rheology)
{
    forAll(segregation_, k)
    {
        f_.append(pairField("granularMixture:f" + Foam::name(k), dimVelocity));
    }
    forAll(diffusion_, k)
    {
        D_.append
        (
            pairField("granularMixture:D" + Foam::name(k), dimArea/dimTime)
        );
    }
}


// * * * * * * * * * * * * * * * Member Functions  * * * * * * * * * * * * * //

void Foam::granularPairFluxes::correct(const granularState& state)
{
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
}


void Foam::granularPairFluxes::relativeFluxes
(
    const PtrList<volScalarField>& alphas,
    const vector& gHat,
    const granularAir& air,
    const surfaceScalarField& phi,
    List<labelPair>& pairs,
    PtrList<surfaceScalarField>& phirs
) const
{
    pairs.clear();
    phirs.clear();

    // Grain pairs: the smaller phase moves along g (2.13), (2.19)
    const surfaceScalarField gSf(gHat & mesh_.Sf());
    forAll(segregation_, k)
    {
        const segregationVelocity& law = segregation_[k];
        const label i = 1 + law.small();
        const label j = 1 + law.large();
        pairs.append(labelPair(i, j));
        phirs.append
        (
            new surfaceScalarField
            (
                law.faceValues(f_[k], alphas[i] + alphas[j])*gSf
            )
        );
    }

    air.relativeFluxes(alphas, phi, pairs, phirs);

    for (surfaceScalarField& phir : phirs)
    {
        zeroUncoupled(phir);
    }
}


void Foam::granularPairFluxes::add
(
    const PtrList<volScalarField>& alphas,
    const List<labelPair>& pairs,
    const PtrList<surfaceScalarField>& phirs,
    PtrList<surfaceScalarField>& alphaPhis,
    PtrList<surfaceScalarField>* relPhis
) const
{
    const word alpharScheme("div(phirb,alpha)");

    // (2.13): one flux per pair, +F for i and -F for j
    forAll(pairs, k)
    {
        const label i = pairs[k].first();
        const label j = pairs[k].second();
        const surfaceScalarField F
        (
            fvc::flux
            (
                -fvc::flux(-phirs[k], alphas[j], alpharScheme),
                alphas[i],
                alpharScheme
            )
        );
        alphaPhis[i] += F;
        alphaPhis[j] -= F;
        if (relPhis)
        {
            (*relPhis)[i] += F;
            (*relPhis)[j] -= F;
        }
    }

    // (2.15): D^i = D_ij (phi^j grad phi^i - phi^i grad phi^j), a flux -D^i
    forAll(diffusion_, k)
    {
        const label i = 1 + diffusion_[k].small();
        const label j = 1 + diffusion_[k].large();
        const volScalarField& ai = alphas[i];
        const volScalarField& aj = alphas[j];

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
        if (relPhis)
        {
            (*relPhis)[i] += Fd;
            (*relPhis)[j] -= Fd;
        }
    }
}


Foam::tmp<Foam::scalarField> Foam::granularPairFluxes::segregationRate
(
    const PtrList<volScalarField>& alphas,
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
                alphas[pairs[k].first()] + alphas[pairs[k].second()]
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


Foam::tmp<Foam::scalarField> Foam::granularPairFluxes::diffusionRate
(
    const scalarField& G
) const
{
    auto tdiff = tmp<scalarField>::New(mesh_.nCells(), Zero);
    for (const volScalarField& D : D_)
    {
        tdiff.ref() += D.primitiveField()*G;
    }
    return tdiff;
}


void Foam::granularPairFluxes::zeroUncoupled(surfaceScalarField& sf)
{
    for (fvsPatchScalarField& psf : sf.boundaryFieldRef())
    {
        if (!psf.coupled())
        {
            psf = Zero;
        }
    }
}


Foam::scalar Foam::granularPairFluxes::fluxSum
(
    const PtrList<surfaceScalarField>& fluxes
)
{
    // Face by face over the internal faces and every patch, without
    // temporary fields: this is taken twice per sub-cycle
    scalar sumMax = 0;
    scalar largest = 0;
    const label nPatches = fluxes[0].boundaryField().size();
    for (label part = -1; part < nPatches; ++part)
    {
        List<const scalarField*> F(fluxes.size());
        forAll(fluxes, i)
        {
            F[i] =
                part < 0
              ? &fluxes[i].primitiveField()
              : &fluxes[i].boundaryField()[part];
        }
        forAll(*F[0], facei)
        {
            scalar sum = 0;
            forAll(F, i)
            {
                const scalar f = (*F[i])[facei];
                sum += f;
                largest = max(largest, mag(f));
            }
            sumMax = max(sumMax, mag(sum));
        }
    }
    reduce(sumMax, maxOp<scalar>());
    reduce(largest, maxOp<scalar>());
    return sumMax/max(largest, VSMALL);
}


void Foam::granularPairFluxes::read
(
    const dictionary& dict,
    const granularRheology& rheology
)
{
    segregation_.read(dict, "segregation", rheology);
    diffusion_.read(dict, "diffusion", rheology);
}


// ************************************************************************* //
