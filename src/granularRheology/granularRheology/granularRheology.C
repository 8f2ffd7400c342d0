/*---------------------------------------------------------------------------*\
    granularSegregationFoam: coupled mu(I) rheology and size segregation
    Copyright (C) 2026 The granularSegregationFoam authors
    License: GNU General Public License v3 or later (see LICENSE)
\*---------------------------------------------------------------------------*/

#include "granularRheology.H"
#include "granularInput.H"

// * * * * * * * * * * * * * * Static Data Members * * * * * * * * * * * * * //

namespace Foam
{
    defineTypeNameAndDebug(granularRheology, 0);
}

const Foam::Enum<Foam::granularRheology::mixtureRule>
Foam::granularRheology::mixtureRuleNames
({
    { mixtureRule::weightedFriction, "weightedFriction" },
    { mixtureRule::weightedParameters, "weightedParameters" },
});


// * * * * * * * * * * * * * * * * Constructors  * * * * * * * * * * * * * * //

Foam::granularRheology::granularRheology(const dictionary& dict)
:
    dict_(dict),
    rhoStar_(granularInput::readPositive(dict, "rhoStar", dimDensity)),
    Phi_(granularInput::readPositive(dict, "Phi")),
    etaMax_
    (
        granularInput::readPositive(dict, "etaMax", dimPressure*dimTime)
    ),
    pMin_
    (
        granularInput::readPositiveOrDefault(dict, "pMin", dimPressure, 1e-8)
    ),
    rule_
    (
        granularInput::readEnum
        (
            dict, "mixtureRule",
            mixtureRuleNames, mixtureRule::weightedFriction
        )
    )
{
    if (Phi_.value() > 1)
    {
        granularInput::invalid(dict, "Phi", Phi_.value(), "must be <= 1");
    }

    const dictionary& grainsDict = granularInput::subDict
    (
        dict, "grains", "one sub-dictionary per grain phase"
    );
    names_ = grainsDict.toc();

    if (names_.empty())
    {
        FatalIOErrorInFunction(grainsDict)
            << "No grain phase in " << grainsDict.name()
            << ": give one sub-dictionary per grain phase" << nl
            << exit(FatalIOError);
    }

    d_.setSize(names_.size());
    laws_.setSize(names_.size());

    forAll(names_, i)
    {
        if (!grainsDict.isDict(names_[i]))
        {
            FatalIOErrorInFunction(grainsDict)
                << "Entry '" << names_[i] << "' of " << grainsDict.name()
                << " is not a grain phase sub-dictionary" << nl
                << exit(FatalIOError);
        }
        const dictionary& phaseDict = grainsDict.subDict(names_[i]);
        d_[i] = granularInput::readPositive(phaseDict, "d", dimLength).value();
        laws_.set(i, frictionLaw::New(phaseDict));
    }

    if (rule_ == mixtureRule::weightedParameters)
    {
        forAll(laws_, i)
        {
            if (laws_[i].type() != laws_[0].type())
            {
                FatalIOErrorInFunction(laws_[i].dict())
                    << "mixtureRule weightedParameters (3.4) needs one "
                    << "friction law for all grains: frictionLaw "
                    << laws_[i].type() << " in " << laws_[i].dict().name()
                    << " differs from " << laws_[0].type() << " of "
                    << names_[0] << nl << exit(FatalIOError);
            }
        }
    }
}


// * * * * * * * * * * * * * * * Member Functions  * * * * * * * * * * * * * //


void Foam::granularRheology::read(const dictionary& dict)
{
    const dictionary& grainsDict = granularInput::subDict
    (
        dict, "grains", "one sub-dictionary per grain phase"
    );
    if (grainsDict.toc() != names_)
    {
        FatalIOErrorInFunction(grainsDict)
            << "The grain phases of " << grainsDict.name() << " changed"
            << " during the run, from " << names_ << " to "
            << grainsDict.toc() << ": the phase fields are read at the"
            << " start only; stop the run and start it again" << nl
            << exit(FatalIOError);
    }
    granularRheology updated(dict);
    dict_ = updated.dict_;
    rhoStar_ = updated.rhoStar_;
    Phi_ = updated.Phi_;
    etaMax_ = updated.etaMax_;
    pMin_ = updated.pMin_;
    rule_ = updated.rule_;
    d_ = updated.d_;
    laws_.transfer(updated.laws_);
}

void Foam::granularRheology::grainFractions
(
    const UPtrList<const scalarField>& alphas,
    PtrList<scalarField>& w
) const
{
    const label n = nGrains();
    const label nPoints = alphas[0].size();

    w.setSize(n);
    forAll(w, k)
    {
        if (!w.set(k) || w[k].size() != nPoints)
        {
            w.set(k, new scalarField(nPoints));
        }
    }

    for (label i = 0; i < nPoints; ++i)
    {
        scalar sum = 0;
        for (label k = 0; k < n; ++k)
        {
            sum += max(alphas[k][i], scalar(0));
        }

        if (sum > ROOTVSMALL)
        {
            for (label k = 0; k < n; ++k)
            {
                w[k][i] = max(alphas[k][i], scalar(0))/sum;
            }
        }
        else
        {
            for (label k = 0; k < n; ++k)
            {
                w[k][i] = 1.0/n;
            }
        }
    }
}


void Foam::granularRheology::meanDiameter
(
    const UPtrList<const scalarField>& w,
    scalarField& dbar
) const
{
    // (3.1)
    dbar = 0;
    forAll(d_, k)
    {
        dbar += w[k]*d_[k];
    }
}


void Foam::granularRheology::strainRateNorm
(
    const symmTensorField& D,
    scalarField& normD
)
{
    // (2.4)
    forAll(D, i)
    {
        normD[i] = sqrt(0.5*(D[i] && D[i]));
    }
}


void Foam::granularRheology::inertialNumber
(
    const scalarField& normD,
    const scalarField& p,
    const scalarField& dbar,
    scalarField& I
) const
{
    // (3.2)
    const scalar rhoStar = rhoStar_.value();
    forAll(I, i)
    {
        I[i] = 2*dbar[i]*normD[i]/sqrt(pressure(p[i])/rhoStar);
    }
}


void Foam::granularRheology::friction
(
    const scalarField& I,
    const UPtrList<const scalarField>& w,
    scalarField& mu,
    scalarField* dmudI
) const
{
    if (rule_ == mixtureRule::weightedParameters)
    {
        // (3.4)
        UPtrList<const frictionLaw> laws(laws_.size());
        forAll(laws_, k)
        {
            laws.set(k, &laws_[k]);
        }
        laws_[0].weightedCoeffs(I, laws, w, mu, dmudI);
        return;
    }

    // (3.3)
    scalarField muk(I.size());
    mu = 0;
    if (dmudI)
    {
        *dmudI = 0;
    }
    forAll(laws_, k)
    {
        laws_[k].mu(I, muk);
        mu += w[k]*muk;
        if (dmudI)
        {
            laws_[k].dmudI(I, muk);
            *dmudI += w[k]*muk;
        }
    }
}


Foam::scalar Foam::granularRheology::inverseFriction
(
    const scalarList& w,
    const scalar muValue
) const
{
    // One phase alone: its own law's inverse (5.5)
    forAll(w, k)
    {
        if (w[k] == 1)
        {
            return laws_[k].inverse(muValue);
        }
    }

    // A mixture: (3.3) or (3.4) increases with I, so bisect
    UPtrList<const scalarField> wk(w.size());
    PtrList<scalarField> store(w.size());
    forAll(w, k)
    {
        store.set(k, new scalarField(1, w[k]));
        wk.set(k, &store[k]);
    }
    scalarField I(1, 0.0), mu(1);
    auto excess = [&](const scalar x)
    {
        I[0] = x;
        friction(I, wk, mu);
        return mu[0] - muValue;
    };

    scalar lo = 0, hi = 1;
    if (excess(lo) > 0)
    {
        FatalErrorInFunction
            << "The mixture friction of " << names_ << " with fractions " << w
            << " exceeds " << muValue << " at I = 0: no steady flow"
            << exit(FatalError);
    }
    while (excess(hi) < 0)
    {
        hi *= 2;
        if (hi > 1e12)
        {
            FatalErrorInFunction
                << "The mixture friction of " << names_ << " with fractions "
                << w << " does not reach " << muValue << exit(FatalError);
        }
    }
    for (label iter = 0; iter < 200 && hi - lo > 4*SMALL*hi; ++iter)
    {
        const scalar mid = 0.5*(lo + hi);
        (excess(mid) < 0 ? lo : hi) = mid;
    }
    return 0.5*(lo + hi);
}


void Foam::granularRheology::viscosity
(
    const scalarField& mu,
    const scalarField& p,
    const scalarField& normD,
    scalarField& eta
) const
{
    // (2.3) capped by (4.12), compared before dividing so that |D| = 0 is safe
    const scalar etaMax = etaMax_.value();
    forAll(eta, i)
    {
        const scalar tau = mu[i]*pressure(p[i]);
        eta[i] =
            (tau >= 2*normD[i]*etaMax)
          ? etaMax
          : tau/(2*normD[i]);
    }
}


// ************************************************************************* //
