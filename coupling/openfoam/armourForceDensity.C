/*---------------------------------------------------------------------------*\
    armour-fsi: two-way coupling of armour units with interFoam
\*---------------------------------------------------------------------------*/

#include "armourForceDensity.H"

#include "fvcGrad.H"
#include "fvcLaplacian.H"

#include <cmath>

// * * * * * * * * * * * * * * * Local Functions * * * * * * * * * * * * * * //

namespace
{

// f = -grad(p) + laplacian(muEff, U) on the whole mesh, as OpenFOAM's
// schemes give it: the reference, and the fallback where the face-by-face
// sum below does not reproduce it.
Foam::tmp<Foam::volVectorField> fvcForceDensity
(
    const Foam::volScalarField& p,
    const Foam::volScalarField& muEff,
    const Foam::volVectorField& U
)
{
    return -Foam::fvc::grad(p) + Foam::fvc::laplacian(muEff, U);
}


// f = -grad(p) + laplacian(muEff, U) in the listed cells only, face by
// face: Gauss linear gradient, Gauss linear laplacian with the uncorrected
// surface-normal gradient. On a 100-unit tank the whole-mesh fvc expression
// took ~90 % of the load time, mostly in cells no unit touches. Exact for
// what fvc computes with the default schemes on an orthogonal mesh (there
// the non-orthogonal correction vanishes); forceDensityAgrees() checks
// that on the mesh at hand before it is used.
void faceByFaceForceDensity
(
    const Foam::fvMesh& mesh,
    const Foam::volScalarField& p,
    const Foam::volScalarField& muEff,
    const Foam::volVectorField& U,
    const Foam::labelUList& cells,
    Foam::vectorField& f
)
{
    using namespace Foam;
    const labelUList& own = mesh.owner();
    const labelUList& nei = mesh.neighbour();
    const surfaceScalarField& w = mesh.weights();
    const surfaceScalarField& dc = mesh.nonOrthDeltaCoeffs();
    const surfaceVectorField& Sf = mesh.Sf();
    const surfaceScalarField& magSf = mesh.magSf();
    const label nInternal = mesh.nInternalFaces();
    const polyBoundaryMesh& patches = mesh.boundaryMesh();

    // Face values on each patch, as fvc takes them: the boundary value, or
    // the weighted mean with the neighbour across a coupled patch.
    PtrList<scalarField> pFace(patches.size());
    PtrList<scalarField> muFace(patches.size());
    PtrList<vectorField> snGradU(patches.size());
    forAll(patches, pi)
    {
        const fvPatchScalarField& pb = p.boundaryField()[pi];
        const fvPatchScalarField& mub = muEff.boundaryField()[pi];
        const fvPatchVectorField& Ub = U.boundaryField()[pi];
        if (pb.coupled())
        {
            const scalarField& wp = w.boundaryField()[pi];
            pFace.set
            (
                pi,
                new scalarField
                (
                    wp*pb.patchInternalField() + (1.0 - wp)*pb.patchNeighbourField()
                )
            );
            muFace.set
            (
                pi,
                new scalarField
                (
                    wp*mub.patchInternalField() + (1.0 - wp)*mub.patchNeighbourField()
                )
            );
            snGradU.set(pi, new vectorField(Ub.snGrad(dc.boundaryField()[pi])));
        }
        else
        {
            pFace.set(pi, new scalarField(pb));
            muFace.set(pi, new scalarField(mub));
            snGradU.set(pi, new vectorField(Ub.snGrad()));
        }
    }

    const cellList& cellFaces = mesh.cells();
    const scalarField& V = mesh.V();
    forAll(cells, k)
    {
        const label c = cells[k];
        vector pressure = Zero;
        vector viscous = Zero;
        for (const label face : cellFaces[c])
        {
            if (face < nInternal)
            {
                const label o = own[face];
                const label n = nei[face];
                const scalar sign = (o == c) ? 1.0 : -1.0;
                const scalar wf = w[face];
                pressure += sign*Sf[face]*(wf*p[o] + (1.0 - wf)*p[n]);
                viscous +=
                    sign*(wf*muEff[o] + (1.0 - wf)*muEff[n])*magSf[face]
                   *dc[face]*(U[n] - U[o]);
                continue;
            }
            const label pi = patches.whichPatch(face);
            const label i = face - patches[pi].start();
            if (i >= Sf.boundaryField()[pi].size())
            {
                continue; // empty patch: no flux through it
            }
            pressure += Sf.boundaryField()[pi][i]*pFace[pi][i];
            viscous += muFace[pi][i]*magSf.boundaryField()[pi][i]*snGradU[pi][i];
        }
        f[k] = (viscous - pressure)/V[c];
    }
}


// The face-by-face force density against fvc's, on smooth non-linear test
// fields (the real ones may be at rest at the first step) with the real
// mu_eff, in every cell of every rank: true when they agree to rounding.
bool forceDensityAgrees(const Foam::fvMesh& mesh, const Foam::volScalarField& muEff)
{
    using namespace Foam;
    const IOobject io
    (
        "armourCheck",
        mesh.time().timeName(),
        mesh,
        IOobject::NO_READ,
        IOobject::NO_WRITE,
        false
    );
    volScalarField p
    (
        IOobject(io, "armourCheckP"),
        mesh,
        dimensionedScalar(dimPressure, Zero),
        "calculated"
    );
    volVectorField U
    (
        IOobject(io, "armourCheckU"),
        mesh,
        dimensionedVector(dimVelocity, Zero),
        "calculated"
    );
    const auto pOf = [](const vector& x)
    {
        return 1e4*(1.0 + x.x()*x.x() + 0.5*x.y()*x.z() + std::sin(3.0*x.z()));
    };
    const auto UOf = [](const vector& x)
    {
        return vector
        (
            std::sin(2.0*x.y()) + x.z()*x.z(),
            x.x()*x.z() - std::cos(x.x()),
            x.x()*x.x()*x.y() + 0.3*x.z()
        );
    };
    forAll(mesh.C(), i)
    {
        p[i] = pOf(mesh.C()[i]);
        U[i] = UOf(mesh.C()[i]);
    }
    forAll(mesh.boundary(), pi)
    {
        if (p.boundaryField()[pi].coupled())
        {
            continue;
        }
        const vectorField& Cf = mesh.C().boundaryField()[pi];
        forAll(Cf, i)
        {
            p.boundaryFieldRef()[pi][i] = pOf(Cf[i]);
            U.boundaryFieldRef()[pi][i] = UOf(Cf[i]);
        }
    }
    p.correctBoundaryConditions();
    U.correctBoundaryConditions();

    const volVectorField reference(fvcForceDensity(p, muEff, U));
    labelList all(mesh.nCells());
    forAll(all, i)
    {
        all[i] = i;
    }
    vectorField f(mesh.nCells());
    faceByFaceForceDensity(mesh, p, muEff, U, all, f);
    const scalar scale = returnReduce(gMax(mag(reference.primitiveField())), maxOp<scalar>());
    const scalar difference = returnReduce(gMax(mag(f - reference.primitiveField())), maxOp<scalar>());
    return difference <= 1e-9*scale;
}


} // End anonymous namespace


// * * * * * * * * * * * * * * * Member Functions  * * * * * * * * * * * * * //

const std::vector<Eigen::Vector3d>& armourFoam::forceDensity::compute
(
    const Foam::fvMesh& mesh,
    const Foam::volScalarField& rho,
    const Foam::volVectorField& U,
    const std::vector<int>& body
)
{
    using namespace Foam;
    const volScalarField& p = mesh.lookupObject<volScalarField>("p");

    // mu_eff = rho (nu + nut); nut only where a turbulence model made one.
    volScalarField muEff
    (
        "armourMuEff",
        rho*mesh.lookupObject<volScalarField>("nu")
    );
    if (mesh.foundObject<volScalarField>("nut"))
    {
        muEff += rho*mesh.lookupObject<volScalarField>("nut");
    }
    if (method_ == method::unchecked)
    {
        const bool agrees = forceDensityAgrees(mesh, muEff);
        method_ = agrees ? method::faceByFace : method::fvc;
        Info<< "    armourCoupling: force density "
            << (agrees
                ? "face by face in the units' cells (checked against fvc)"
                : "by fvc on the whole mesh (the face-by-face sum differs "
                  "from fvc here: non-orthogonal mesh or other schemes)")
            << endl;
    }

    f_.assign(mesh.nCells(), Eigen::Vector3d::Zero());
    if (method_ == method::faceByFace)
    {
        DynamicList<label> cells(mesh.nCells()/8);
        for (std::size_t i = 0; i < body.size(); ++i)
        {
            if (body[i] >= 0)
            {
                cells.append(label(i));
            }
        }
        vectorField f(cells.size());
        faceByFaceForceDensity(mesh, p, muEff, U, cells, f);
        forAll(cells, k)
        {
            f_[cells[k]] = Eigen::Vector3d(f[k].x(), f[k].y(), f[k].z());
        }
    }
    else
    {
        const volVectorField f(fvcForceDensity(p, muEff, U));
        forAll(f, i)
        {
            f_[i] = Eigen::Vector3d(f[i].x(), f[i].y(), f[i].z());
        }
    }
    return f_;
}


// ************************************************************************* //
