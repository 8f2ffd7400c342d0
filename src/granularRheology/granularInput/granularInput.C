/*---------------------------------------------------------------------------*\
    granularSegregationFoam: coupled mu(I) rheology and size segregation
    Copyright (C) 2026 The granularSegregationFoam authors
    License: GNU General Public License v3 or later (see LICENSE)
\*---------------------------------------------------------------------------*/

#include "granularInput.H"
#include "IOdictionary.H"
#include "Time.H"
#include "volFields.H"
#include "OStringStream.H"

// * * * * * * * * * * * * * * * Global Functions  * * * * * * * * * * * * * //

void Foam::granularInput::invalid
(
    const dictionary& dict,
    const word& keyword,
    const scalar value,
    const string& requirement
)
{
    FatalIOErrorInFunction(dict)
        << "Invalid value of keyword '" << keyword << "' in dictionary "
        << dict.name() << ": " << keyword << " = " << value
        << " (" << requirement.c_str() << ")" << nl
        << exit(FatalIOError);

    // exit() returns only when FatalIOError throws instead of exiting
    ::abort();
}


namespace
{
    // The tokens of an entry as written, separated by spaces
    Foam::string entryText(const Foam::entry& e)
    {
        Foam::OStringStream text;
        for (const Foam::token& t : e.stream())
        {
            text << (text.str().empty() ? "" : " ") << t;
        }
        return text.str();
    }

    Foam::dimensionedScalar readChecked
    (
        const Foam::dictionary& dict,
        const Foam::word& keyword,
        const Foam::dimensionSet& dims,
        const bool strict
    )
    {
        using namespace Foam;

        if (!dict.found(keyword))
        {
            FatalIOErrorInFunction(dict)
                << "Missing keyword '" << keyword << "' in dictionary "
                << dict.name() << nl << exit(FatalIOError);
        }

        // A dimensioned scalar ends with its value: a word there ('abc')
        // would be read as a missing number, "attempt to read beyond EOF"
        const entry& e = dict.lookupEntry(keyword, keyType::LITERAL);
        if (e.isDict() || !e.stream().size() || !e.stream().last().isNumber())
        {
            FatalIOErrorInFunction(dict)
                << "Invalid value of keyword '" << keyword << "' in dictionary "
                << dict.name() << ": " << keyword << " = "
                << (e.isDict() ? string("a sub-dictionary") : entryText(e)).c_str()
                << " (a number is needed)" << nl << exit(FatalIOError);
        }

        const dimensionedScalar value(keyword, dims, dict);

        if (!std::isfinite(value.value()))
        {
            granularInput::invalid(dict, keyword, value.value(), "not finite");
        }
        if (strict ? value.value() <= 0 : value.value() < 0)
        {
            granularInput::invalid
            (
                dict, keyword, value.value(), strict ? "must be > 0" : "must be >= 0"
            );
        }
        return value;
    }

    Foam::dimensionedScalar readCheckedOrDefault
    (
        const Foam::dictionary& dict,
        const Foam::word& keyword,
        const Foam::dimensionSet& dims,
        const bool strict,
        const Foam::scalar deflt
    )
    {
        if (!dict.found(keyword))
        {
            return Foam::dimensionedScalar(keyword, dims, deflt);
        }
        return readChecked(dict, keyword, dims, strict);
    }
}


const Foam::dictionary& Foam::granularInput::subDict
(
    const dictionary& dict,
    const word& keyword,
    const string& holds
)
{
    const entry* e = dict.findEntry(keyword, keyType::LITERAL);
    if (!e)
    {
        FatalIOErrorInFunction(dict)
            << "Missing sub-dictionary '" << keyword << "' in " << dict.name()
            << " (" << holds.c_str() << ")" << nl << exit(FatalIOError);
    }
    if (!e->isDict())
    {
        FatalIOErrorInFunction(dict)
            << "Invalid entry '" << keyword << "' in " << dict.name() << ": "
            << keyword << " = " << entryText(*e).c_str()
            << " is not a sub-dictionary (" << holds.c_str() << ")" << nl
            << exit(FatalIOError);
    }
    return e->dict();
}


Foam::dimensionedScalar Foam::granularInput::readPositive
(
    const dictionary& dict,
    const word& keyword,
    const dimensionSet& dims
)
{
    return readChecked(dict, keyword, dims, true);
}


Foam::dimensionedScalar Foam::granularInput::readPositiveOrDefault
(
    const dictionary& dict,
    const word& keyword,
    const dimensionSet& dims,
    const scalar deflt
)
{
    return readCheckedOrDefault(dict, keyword, dims, true, deflt);
}


Foam::dimensionedScalar Foam::granularInput::readNonNegative
(
    const dictionary& dict,
    const word& keyword,
    const dimensionSet& dims
)
{
    return readChecked(dict, keyword, dims, false);
}


Foam::dimensionedScalar Foam::granularInput::readNonNegativeOrDefault
(
    const dictionary& dict,
    const word& keyword,
    const dimensionSet& dims,
    const scalar deflt
)
{
    return readCheckedOrDefault(dict, keyword, dims, false, deflt);
}


Foam::word Foam::granularInput::readVectorOrWord
(
    const dictionary& dict,
    const word& keyword,
    const wordList& words,
    vector& v
)
{
    ITstream& is = dict.lookup(keyword);
    token t(is);
    if (!t.isWord())
    {
        is.putBack(t);
        is >> v;
        return word::null;
    }
    if (!words.found(t.wordToken()))
    {
        FatalIOErrorInFunction(dict)
            << "Invalid value of keyword '" << keyword << "' in dictionary "
            << dict.name() << ": " << keyword << " = " << t.wordToken()
            << " (a vector or one of " << flatOutput(words) << ")" << nl
            << exit(FatalIOError);
    }
    return t.wordToken();
}


Foam::word Foam::granularInput::readWord
(
    const dictionary& dict,
    const word& keyword,
    const wordList& words,
    const word& deflt
)
{
    const word value(dict.getOrDefault<word>(keyword, deflt));
    if (!words.found(value))
    {
        FatalIOErrorInFunction(dict)
            << "Invalid value of keyword '" << keyword << "' in dictionary "
            << dict.name() << ": " << keyword << " = " << value
            << " (one of " << flatOutput(words) << ")" << nl
            << exit(FatalIOError);
    }
    return value;
}


const Foam::dictionary& Foam::granularInput::coeffsDict
(
    const dictionary& dict,
    const word& modelType
)
{
    return dict.optionalSubDict(modelType + "Coeffs");
}


void Foam::granularInput::requireFields
(
    const dictionary& dict,
    const word& keyword,
    const wordList& names,
    const objectRegistry& db
)
{
    for (const word& name : names)
    {
        if (!db.foundObject<volScalarField>(name))
        {
            OStringStream value;
            if (names.size() == 1)
            {
                value << name;
            }
            else
            {
                value << names;
            }
            FatalIOErrorInFunction(dict)
                << "Invalid value of keyword '" << keyword << "' in dictionary "
                << dict.name() << ": " << keyword << " = "
                << value.str().c_str() << ": no field " << name
                << " (the fields are "
                << flatOutput(db.sortedNames<volScalarField>()) << ")" << nl
                << exit(FatalIOError);
        }
    }
}


Foam::dictionary Foam::granularInput::readProperties(const objectRegistry& db)
{
    return IOdictionary
    (
        IOobject
        (
            "granularProperties",
            db.time().constant(),
            db,
            IOobject::MUST_READ,
            IOobject::NO_WRITE,
            false
        )
    );
}


// ************************************************************************* //
