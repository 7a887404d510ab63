/*---------------------------------------------------------------------------*\
    armour-fsi: absorbing outlet for long waves
    (armourShallowWaterAbsorptionFvPatchVectorField.H)
\*---------------------------------------------------------------------------*/

#include "armourShallowWaterAbsorptionFvPatchVectorField.H"
#include "addToRunTimeSelectionTable.H"
#include "volFields.H"

namespace
{

bool readFormulation(const Foam::dictionary& dict)
{
    const Foam::word f(dict.getOrDefault<Foam::word>("formulation", "linear"));
    if (f != "linear" && f != "nonlinear")
    {
        FatalIOErrorInFunction(dict)
            << "formulation must be linear or nonlinear, got " << f
            << Foam::exit(Foam::FatalIOError);
    }
    return f == "nonlinear";
}

}


Foam::armourShallowWaterAbsorptionFvPatchVectorField::
armourShallowWaterAbsorptionFvPatchVectorField
(
    const fvPatch& p,
    const DimensionedField<vector, volMesh>& iF
)
:
    fixedValueFvPatchVectorField(p, iF),
    h_(1),
    nonlinear_(false),
    celerity_(0),
    alphaName_("alpha.water")
{}


Foam::armourShallowWaterAbsorptionFvPatchVectorField::
armourShallowWaterAbsorptionFvPatchVectorField
(
    const fvPatch& p,
    const DimensionedField<vector, volMesh>& iF,
    const dictionary& dict
)
:
    fixedValueFvPatchVectorField(p, iF, dict),
    h_(dict.get<scalar>("waterDepth")),
    nonlinear_(readFormulation(dict)),
    celerity_(dict.getOrDefault<scalar>("celerity", 0)),
    alphaName_(dict.getOrDefault<word>("alpha", "alpha.water"))
{
    if (h_ <= 0)
    {
        FatalIOErrorInFunction(dict)
            << "waterDepth must be positive, got " << h_ << exit(FatalIOError);
    }
    if (celerity_ < 0 || (celerity_ > 0 && nonlinear_))
    {
        FatalIOErrorInFunction(dict)
            << "celerity must be positive and goes with formulation linear,"
            << " got " << celerity_ << exit(FatalIOError);
    }
}


Foam::armourShallowWaterAbsorptionFvPatchVectorField::
armourShallowWaterAbsorptionFvPatchVectorField
(
    const armourShallowWaterAbsorptionFvPatchVectorField& ptf,
    const fvPatch& p,
    const DimensionedField<vector, volMesh>& iF,
    const fvPatchFieldMapper& mapper
)
:
    fixedValueFvPatchVectorField(ptf, p, iF, mapper),
    h_(ptf.h_),
    nonlinear_(ptf.nonlinear_),
    celerity_(ptf.celerity_),
    alphaName_(ptf.alphaName_)
{}


Foam::armourShallowWaterAbsorptionFvPatchVectorField::
armourShallowWaterAbsorptionFvPatchVectorField
(
    const armourShallowWaterAbsorptionFvPatchVectorField& ptf
)
:
    fixedValueFvPatchVectorField(ptf),
    h_(ptf.h_),
    nonlinear_(ptf.nonlinear_),
    celerity_(ptf.celerity_),
    alphaName_(ptf.alphaName_)
{}


Foam::armourShallowWaterAbsorptionFvPatchVectorField::
armourShallowWaterAbsorptionFvPatchVectorField
(
    const armourShallowWaterAbsorptionFvPatchVectorField& ptf,
    const DimensionedField<vector, volMesh>& iF
)
:
    fixedValueFvPatchVectorField(ptf, iF),
    h_(ptf.h_),
    nonlinear_(ptf.nonlinear_),
    celerity_(ptf.celerity_),
    alphaName_(ptf.alphaName_)
{}


void Foam::armourShallowWaterAbsorptionFvPatchVectorField::updateCoeffs()
{
    if (updated())
    {
        return;
    }

    const vector g(armourWaves::gravity(patch()));
    const armourWaves::patchFrame frame(patch(), g);

    const volScalarField& alpha =
        db().lookupObject<volScalarField>(alphaName_);
    const scalarField alphaCells
    (
        alpha.boundaryField()[patch().index()].patchInternalField()
    );
    const scalar level = frame.waterLevel(patch(), alphaCells);
    scalar eta = level - h_;
    if (celerity_ > 0)
    {
        // The outgoing wave reaches the patch d/c after the cell centres.
        const Time& time = db().time();
        if (time.timeIndex() != indexNow_)
        {
            etaPrev_ = etaNow_;
            timePrev_ = timeNow_;
            indexPrev_ = indexNow_;
            indexNow_ = time.timeIndex();
        }
        etaNow_ = eta;
        timeNow_ = time.value();
        if (indexPrev_ == indexNow_ - 1 && timeNow_ > timePrev_)
        {
            const scalar d = gAverage(1.0/patch().deltaCoeffs());
            eta -= d/celerity_*(etaNow_ - etaPrev_)/(timeNow_ - timePrev_);
        }
    }

    const scalar uOut =
        nonlinear_
      ? eta*Foam::sqrt(mag(g)/max(level, SMALL))
      : celerity_ > 0
      ? eta*celerity_/h_
      : eta*Foam::sqrt(mag(g)/h_);

    // frame.ex points into the domain; the wave leaves along -ex.
    const scalarField wet(frame.wetFraction(level));
    vectorField Up(patch().size(), Zero);
    forAll(Up, facei)
    {
        if (wet[facei] > 0)
        {
            Up[facei] = -uOut*frame.ex;
        }
    }

    operator==(Up);

    fixedValueFvPatchVectorField::updateCoeffs();
}


void Foam::armourShallowWaterAbsorptionFvPatchVectorField::write
(
    Ostream& os
) const
{
    fvPatchVectorField::write(os);
    os.writeEntry("waterDepth", h_);
    os.writeEntry("formulation", word(nonlinear_ ? "nonlinear" : "linear"));
    if (celerity_ > 0)
    {
        os.writeEntry("celerity", celerity_);
    }
    os.writeEntry("alpha", alphaName_);
    writeEntry("value", os);
}


namespace Foam
{
    makePatchTypeField
    (
        fvPatchVectorField,
        armourShallowWaterAbsorptionFvPatchVectorField
    );
}
