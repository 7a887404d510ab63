/*---------------------------------------------------------------------------*\
    armour-fsi: solitary wave velocity inlet
    (armourSolitaryVelocityFvPatchVectorField.H)
\*---------------------------------------------------------------------------*/

#include "armourSolitaryVelocityFvPatchVectorField.H"
#include "addToRunTimeSelectionTable.H"
#include "volFields.H"
#include "Switch.H"

Foam::armourSolitaryVelocityFvPatchVectorField::
armourSolitaryVelocityFvPatchVectorField
(
    const fvPatch& p,
    const DimensionedField<vector, volMesh>& iF
)
:
    fixedValueFvPatchVectorField(p, iF),
    wave_(),
    activeAbsorption_(false),
    alphaName_("alpha.water")
{}


Foam::armourSolitaryVelocityFvPatchVectorField::
armourSolitaryVelocityFvPatchVectorField
(
    const fvPatch& p,
    const DimensionedField<vector, volMesh>& iF,
    const dictionary& dict
)
:
    fixedValueFvPatchVectorField(p, iF, dict),
    wave_(dict, mag(armourWaves::gravity(p))),
    activeAbsorption_(dict.getOrDefault<bool>("activeAbsorption", false)),
    alphaName_(dict.getOrDefault<word>("alpha", "alpha.water"))
{}


Foam::armourSolitaryVelocityFvPatchVectorField::
armourSolitaryVelocityFvPatchVectorField
(
    const armourSolitaryVelocityFvPatchVectorField& ptf,
    const fvPatch& p,
    const DimensionedField<vector, volMesh>& iF,
    const fvPatchFieldMapper& mapper
)
:
    fixedValueFvPatchVectorField(ptf, p, iF, mapper),
    wave_(ptf.wave_),
    activeAbsorption_(ptf.activeAbsorption_),
    alphaName_(ptf.alphaName_)
{}


Foam::armourSolitaryVelocityFvPatchVectorField::
armourSolitaryVelocityFvPatchVectorField
(
    const armourSolitaryVelocityFvPatchVectorField& ptf
)
:
    fixedValueFvPatchVectorField(ptf),
    wave_(ptf.wave_),
    activeAbsorption_(ptf.activeAbsorption_),
    alphaName_(ptf.alphaName_)
{}


Foam::armourSolitaryVelocityFvPatchVectorField::
armourSolitaryVelocityFvPatchVectorField
(
    const armourSolitaryVelocityFvPatchVectorField& ptf,
    const DimensionedField<vector, volMesh>& iF
)
:
    fixedValueFvPatchVectorField(ptf, iF),
    wave_(ptf.wave_),
    activeAbsorption_(ptf.activeAbsorption_),
    alphaName_(ptf.alphaName_)
{}


void Foam::armourSolitaryVelocityFvPatchVectorField::updateCoeffs()
{
    if (updated())
    {
        return;
    }

    const vector g(armourWaves::gravity(patch()));
    const armourWaves::patchFrame frame(patch(), g);
    const scalar t = db().time().value();

    // One surface level for the whole patch: the patch is a vertical plane
    // at one x, so eta differs between faces only by round-off.
    const scalar etaTarget = wave_.eta(0, t);
    const scalar level = wave_.h() + etaTarget;

    scalar uCorr = 0;
    scalar wetLevel = level;
    if (activeAbsorption_)
    {
        const volScalarField& alpha =
            db().lookupObject<volScalarField>(alphaName_);
        const scalarField alphaCells
        (
            alpha.boundaryField()[patch().index()].patchInternalField()
        );
        const scalar measured = frame.waterLevel(patch(), alphaCells);
        uCorr = Foam::sqrt(mag(g)/wave_.h())*(level - measured);
        wetLevel = max(level, measured);
    }

    const scalarField wet(frame.wetFraction(wetLevel));
    vectorField Up(patch().size(), Zero);
    forAll(Up, facei)
    {
        if (wet[facei] > 0)
        {
            const vector2D uw =
                wave_.velocity(frame.s[facei], t, min(frame.zc[facei], level));
            Up[facei] = (uw.x() + uCorr)*frame.ex + uw.y()*frame.ez;
        }
    }

    operator==(Up);

    fixedValueFvPatchVectorField::updateCoeffs();
}


void Foam::armourSolitaryVelocityFvPatchVectorField::write(Ostream& os) const
{
    fvPatchVectorField::write(os);
    wave_.write(os);
    os.writeEntry("activeAbsorption", Switch(activeAbsorption_));
    os.writeEntry("alpha", alphaName_);
    writeEntry("value", os);
}


namespace Foam
{
    makePatchTypeField
    (
        fvPatchVectorField,
        armourSolitaryVelocityFvPatchVectorField
    );
}
