/*---------------------------------------------------------------------------*\
    armour-fsi: solitary wave phase-fraction inlet
    (armourSolitaryAlphaFvPatchScalarField.H)
\*---------------------------------------------------------------------------*/

#include "armourSolitaryAlphaFvPatchScalarField.H"
#include "addToRunTimeSelectionTable.H"

Foam::armourSolitaryAlphaFvPatchScalarField::
armourSolitaryAlphaFvPatchScalarField
(
    const fvPatch& p,
    const DimensionedField<scalar, volMesh>& iF
)
:
    fixedValueFvPatchScalarField(p, iF),
    wave_()
{}


Foam::armourSolitaryAlphaFvPatchScalarField::
armourSolitaryAlphaFvPatchScalarField
(
    const fvPatch& p,
    const DimensionedField<scalar, volMesh>& iF,
    const dictionary& dict
)
:
    fixedValueFvPatchScalarField(p, iF, dict),
    wave_(dict, mag(armourWaves::gravity(p)))
{}


Foam::armourSolitaryAlphaFvPatchScalarField::
armourSolitaryAlphaFvPatchScalarField
(
    const armourSolitaryAlphaFvPatchScalarField& ptf,
    const fvPatch& p,
    const DimensionedField<scalar, volMesh>& iF,
    const fvPatchFieldMapper& mapper
)
:
    fixedValueFvPatchScalarField(ptf, p, iF, mapper),
    wave_(ptf.wave_)
{}


Foam::armourSolitaryAlphaFvPatchScalarField::
armourSolitaryAlphaFvPatchScalarField
(
    const armourSolitaryAlphaFvPatchScalarField& ptf
)
:
    fixedValueFvPatchScalarField(ptf),
    wave_(ptf.wave_)
{}


Foam::armourSolitaryAlphaFvPatchScalarField::
armourSolitaryAlphaFvPatchScalarField
(
    const armourSolitaryAlphaFvPatchScalarField& ptf,
    const DimensionedField<scalar, volMesh>& iF
)
:
    fixedValueFvPatchScalarField(ptf, iF),
    wave_(ptf.wave_)
{}


void Foam::armourSolitaryAlphaFvPatchScalarField::updateCoeffs()
{
    if (updated())
    {
        return;
    }

    const armourWaves::patchFrame frame
    (
        patch(),
        armourWaves::gravity(patch())
    );
    const scalar t = db().time().value();

    operator==(frame.wetFraction(wave_.h() + wave_.eta(0, t)));

    fixedValueFvPatchScalarField::updateCoeffs();
}


void Foam::armourSolitaryAlphaFvPatchScalarField::write(Ostream& os) const
{
    fvPatchScalarField::write(os);
    wave_.write(os);
    writeEntry("value", os);
}


namespace Foam
{
    makePatchTypeField
    (
        fvPatchScalarField,
        armourSolitaryAlphaFvPatchScalarField
    );
}
