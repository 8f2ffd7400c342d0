/*---------------------------------------------------------------------------*\
    granularSegregationFoam: coupled mu(I) rheology and size segregation
    Copyright (C) 2026 The granularSegregationFoam authors
    License: GNU General Public License v3 or later (see LICENSE)
\*---------------------------------------------------------------------------*/

#include "andersonAcceleration.H"
#include "scalarMatrices.H"
#include "granularInput.H"

// * * * * * * * * * * * * * * * * Constructors  * * * * * * * * * * * * * * //

Foam::andersonAcceleration::andersonAcceleration()
:
    depth_(0)
{}


// * * * * * * * * * * * * * * * Member Functions  * * * * * * * * * * * * * //

void Foam::andersonAcceleration::read(const dictionary& dict)
{
    const label depth = dict.getOrDefault<label>("andersonDepth", 0);
    if (depth < 0)
    {
        granularInput::invalid
        (
            dict, "andersonDepth", depth, ">= 0; 0: no acceleration"
        );
    }
    if (depth != depth_)
    {
        depth_ = depth;
        reset();
    }
}


void Foam::andersonAcceleration::reset()
{
    dF_.clear();
    dG_.clear();
    fLast_.clear();
    gLast_.clear();
}


void Foam::andersonAcceleration::start(const volVectorField& U)
{
    if (depth_)
    {
        x_ = U.primitiveField();
    }
}


void Foam::andersonAcceleration::accelerate
(
    volVectorField& U,
    const volScalarField& rho
)
{
    if (!depth_)
    {
        return;
    }

    const vectorField g(U.primitiveField());
    const vectorField f(g - x_);

    if (fLast_.size())
    {
        // The newest difference at the end, the oldest dropped beyond m
        if (dF_.size() == depth_)
        {
            for (label i = 1; i < depth_; ++i)
            {
                dF_.set(i - 1, dF_.set(i, nullptr));
                dG_.set(i - 1, dG_.set(i, nullptr));
            }
            dF_.resize(depth_ - 1);
            dG_.resize(depth_ - 1);
        }
        dF_.append(new vectorField(f - fLast_));
        dG_.append(new vectorField(g - gLast_));
    }
    fLast_ = f;
    gLast_ = g;

    const label n = dF_.size();
    if (!n)
    {
        return;
    }

    // Normal equations of the least-squares problem in the mass-weighted
    // norm, with a relative regularisation for nearly parallel differences
    const scalarField w(rho.primitiveField()*rho.mesh().V().field());
    scalarSquareMatrix M(n, Zero);
    scalarField gamma(n, Zero);
    for (label i = 0; i < n; ++i)
    {
        for (label j = 0; j <= i; ++j)
        {
            M(i, j) = gSum(w*(dF_[i] & dF_[j]));
            M(j, i) = M(i, j);
        }
        gamma[i] = gSum(w*(dF_[i] & f));
    }
    scalar trace = 0;
    for (label i = 0; i < n; ++i)
    {
        trace += M(i, i);
    }
    for (label i = 0; i < n; ++i)
    {
        M(i, i) += 1e-10*trace/n + VSMALL;
    }
    LUsolve(M, gamma);

    vectorField& x = U.primitiveFieldRef();
    x = g;
    for (label i = 0; i < n; ++i)
    {
        x -= gamma[i]*dG_[i];
    }
    U.correctBoundaryConditions();
}


// ************************************************************************* //
