/*---------------------------------------------------------------------------*\
    armour-fsi: solitary wave theory and patch geometry (armourSolitaryWave.H)
\*---------------------------------------------------------------------------*/

#include "armourSolitaryWave.H"
#include "gravityMeshObject.H"
#include "fvMesh.H"
#include "boundBox.H"
#include "PstreamReduceOps.H"
#include "mathematicalConstants.H"

namespace Foam
{
namespace armourWaves
{

// * * * * * * * * * * * * * * * solitaryWave  * * * * * * * * * * * * * * * //

solitaryWave::solitaryWave()
:
    H_(0),
    h_(1),
    g_(9.81),
    tCrest_(0)
{}


solitaryWave::solitaryWave(const dictionary& dict, const scalar magG)
:
    H_(dict.get<scalar>("waveHeight")),
    h_(dict.get<scalar>("waterDepth")),
    g_(magG),
    tCrest_(0)
{
    if (h_ <= 0 || H_ <= 0 || H_ > 0.78*h_)
    {
        // Solitary waves break near H/h = 0.78; beyond it the theory is void.
        FatalIOErrorInFunction(dict)
            << "need 0 < waveHeight <= 0.78 waterDepth, got waveHeight "
            << H_ << ", waterDepth " << h_ << exit(FatalIOError);
    }
    if (g_ <= 0)
    {
        FatalIOErrorInFunction(dict)
            << "gravity (constant/g) is zero" << exit(FatalIOError);
    }

    // eta(inlet, 0) = 1e-3 H: sech^2(k c t) = 1e-3.
    tCrest_ = dict.getOrDefault<scalar>
    (
        "crestTime",
        Foam::acosh(Foam::sqrt(1000.0))/(k()*c())
    );
}


scalar solitaryWave::k() const
{
    return Foam::sqrt(0.75*H_/(h_*h_*h_));
}


scalar solitaryWave::c() const
{
    return Foam::sqrt(g_*(h_ + H_));
}


scalar solitaryWave::eta(const scalar s, const scalar t) const
{
    const scalar kX = k()*(s - c()*(t - tCrest_));
    // sech^2 underflows harmlessly; cosh overflows past ~710.
    if (mag(kX) > 300)
    {
        return 0;
    }
    return H_/sqr(Foam::cosh(kX));
}


vector2D solitaryWave::velocity
(
    const scalar s,
    const scalar t,
    const scalar zBed
) const
{
    const scalar kX = k()*(s - c()*(t - tCrest_));
    const scalar e = eta(s, t);
    const scalar d = h_ + e;
    const scalar u = c()*e/d;
    const scalar etaX = -2*k()*e*Foam::tanh(kX);
    const scalar dudx = c()*h_*etaX/sqr(d);
    return vector2D(u, -zBed*dudx);
}


void solitaryWave::write(Ostream& os) const
{
    os.writeEntry("waveHeight", H_);
    os.writeEntry("waterDepth", h_);
    os.writeEntry("crestTime", tCrest_);
}


// * * * * * * * * * * * * * * * * patchFrame * * * * * * * * * * * * * * * * //

patchFrame::patchFrame(const fvPatch& p, const vector& g)
:
    ex(Zero),
    ez(-g/(mag(g) + VSMALL)),
    xRef(0),
    zBed(0),
    zSpan(0),
    s(p.size()),
    zc(p.size()),
    zMin(p.size()),
    zMax(p.size())
{
    // Inward normal, made horizontal.
    vector n = -gSum(p.Sf());
    n -= (n & ez)*ez;
    ex = n/(mag(n) + VSMALL);

    const pointField& pts = p.patch().localPoints();
    scalar zLo = GREAT;
    scalar zHi = -GREAT;
    forAll(pts, pi)
    {
        zLo = min(zLo, pts[pi] & ez);
        zHi = max(zHi, pts[pi] & ez);
    }
    reduce(zLo, minOp<scalar>());
    reduce(zHi, maxOp<scalar>());
    zBed = zLo;
    zSpan = zHi - zLo;

    const vectorField& Cf = p.Cf();
    scalar sumX = 0;
    forAll(Cf, facei)
    {
        sumX += Cf[facei] & ex;
    }
    label n0 = p.size();
    reduce(sumX, sumOp<scalar>());
    reduce(n0, sumOp<label>());
    xRef = sumX/max(n0, label(1));

    const faceList& faces = p.patch().localFaces();
    forAll(faces, facei)
    {
        s[facei] = (Cf[facei] & ex) - xRef;
        zc[facei] = (Cf[facei] & ez) - zBed;
        scalar lo = GREAT;
        scalar hi = -GREAT;
        for (const label pi : faces[facei])
        {
            lo = min(lo, pts[pi] & ez);
            hi = max(hi, pts[pi] & ez);
        }
        zMin[facei] = lo - zBed;
        zMax[facei] = hi - zBed;
    }
}


tmp<scalarField> patchFrame::wetFraction(const scalar level) const
{
    tmp<scalarField> tf(new scalarField(zMin.size()));
    scalarField& f = tf.ref();
    forAll(f, facei)
    {
        const scalar dz = zMax[facei] - zMin[facei];
        f[facei] =
            dz > VSMALL
          ? min(max((level - zMin[facei])/dz, scalar(0)), scalar(1))
          : scalar(level > zc[facei] ? 1 : 0);
    }
    return tf;
}


scalar patchFrame::waterLevel
(
    const fvPatch& p,
    const scalarField& alphaCells
) const
{
    const scalarField& magSf = p.magSf();
    scalar wet = 0;
    scalar total = 0;
    forAll(magSf, facei)
    {
        wet += magSf[facei]*min(max(alphaCells[facei], scalar(0)), scalar(1));
        total += magSf[facei];
    }
    reduce(wet, sumOp<scalar>());
    reduce(total, sumOp<scalar>());
    return wet*zSpan/(total + VSMALL);
}


vector gravity(const fvPatch& p)
{
    return meshObjects::gravity::New(p.boundaryMesh().mesh().time()).value();
}

} // End namespace armourWaves
} // End namespace Foam
