#!/usr/bin/env bash
# Rebuild interFoam from Debian's own openfoam source package with tree vectorisation off.
#
# Why (docs/openfoam-v1912.md): Debian 12's openfoam 1912 binaries were compiled by GCC 12 at
# -O3; its loop vectoriser miscompiles the tensor-vector field loop that fvc::reconstruct
# instantiates inside the solver, so interFoam's velocity is wrong in every second
# non-orthogonal cell and water at rest blows up. The loop lives in the solver executable, so
# recompiling the solver alone (against Debian's libraries) with -fno-tree-vectorize cures it.
#
# floatfoam's own C++ (src/solver/*.C: the layered six-DoF motion, docs/morphing.md, the
# body's velocity condition bodyVelocity, docs/openfoam-v1912.md, and the coupling's restraint
# addedMassCompensation, docs/coupling.md) is compiled with the same
# flags and linked into the same executable, so that every run of floatfoam's interFoam has it
# without a library to find at run time; src/solver/interfaceGravity.H (the gravity term at the
# free surface's height, PIMPLE's interfaceGravity: docs/studies/interface-gravity.md) and
# src/solver/couplingConvergence.H (the coupling's iterations ended when the body's motion has
# converged, PIMPLE's couplingTolerance: docs/coupling.md) are compiled into interFoam.C itself.
#
# Output: build/solver/bin/interFoam. Idempotent: does nothing when the binary is there and
# was built from the same flags and sources (src/solver/); a change to those sources alone
# recompiles them and links again (seconds). Needs root for apt (a deb-src entry for Debian
# bookworm).
set -euo pipefail
cd "$(dirname "$0")/.."
OUT=build/solver
BIN=$OUT/bin/interFoam
FLAGS="-std=c++11 -m64 -DOPENFOAM=1912 -DWM_DP -DWM_LABEL_SIZE=32 -DNoRepository -ftemplate-depth-100 -O3 -fno-tree-vectorize -fPIC -w"
STAMP=$OUT/bin/.flags
OWN=(src/solver/*.C)
BUILT="$FLAGS $(cat "${OWN[@]}" src/solver/*.H scripts/build_solver.sh | sha256sum | cut -c1-16)"  # this script: its changes to the sources
if [ -x "$BIN" ] && [ "$(cat "$STAMP" 2>/dev/null)" = "$BUILT" ]; then
  exit 0
fi
mkdir -p "$OUT/download" "$OUT/bin"
rm -f "$STAMP"  # written again after the link: a build cut short is never taken for a whole one

TARBALL=$OUT/download/openfoam_1912.200626.orig.tar.bz2
# its SHA-256 as Debian's openfoam_1912.200626-1.dsc gives it: a damaged file is fetched again
SHA256=c75ca0f04cc4f49708296c1926cbde9d0138b3fef298fed54270dfe29e2df404
if [ -f "$TARBALL" ] && ! echo "$SHA256  $TARBALL" | sha256sum -c --status; then
  echo "build_solver: $TARBALL is damaged (its SHA-256 is not Debian's); fetching it again"
  rm -f "$TARBALL"
fi
if [ ! -f "$TARBALL" ]; then
  sources=/etc/apt/sources.list.d/floatfoam-src.sources
  if [ ! -f "$sources" ]; then
    printf '%s\n' "Types: deb-src" "URIs: http://deb.debian.org/debian" "Suites: bookworm" \
      "Components: main" "Signed-By: /usr/share/keyrings/debian-archive-keyring.gpg" > "$sources"
    apt-get update -qq
  fi
  echo "build_solver: downloading Debian's openfoam source package"
  # into a scratch folder, moved in whole: a download cut short is never taken for the tarball
  rm -rf "$OUT/download.part" && mkdir -p "$OUT/download.part"
  (cd "$OUT/download.part" && apt-get source --download-only -qq -o APT::Sandbox::User=root openfoam=1912.200626-1)
  mv "$OUT"/download.part/* "$OUT/download/" && rm -rf "$OUT/download.part"
fi

SRC=$OUT/source
if [ ! -f "$SRC/.unpacked" ]; then  # marked when whole: an unpacking cut short starts again
  echo "build_solver: unpacking the library headers and the interFoam sources"
  rm -rf "$SRC" && mkdir -p "$SRC"
  tar -xjf "$TARBALL" -C "$SRC" --strip-components=1 \
    --wildcards '*/src/*' '*/applications/solvers/multiphase/interFoam/*' \
    '*/applications/solvers/multiphase/VoF/*'
  # The headers of each library are gathered in its lnInclude folder (what wmake would do).
  find "$SRC/src" -path '*/Make/files' | while read -r files; do
    lib=$(dirname "$(dirname "$files")")
    mkdir -p "$lib/lnInclude"
    find "$lib" -path "$lib/lnInclude" -prune -o -type f \
      \( -name '*.H' -o -name '*.C' -o -name '*.h' \) -print0 |
      xargs -0 -I{} ln -sfr {} "$lib/lnInclude/"
  done
  touch "$SRC/.unpacked"
fi

S=$(realpath "$SRC/src")
includes=""
for lib in OpenFOAM OSspecific/POSIX finiteVolume meshTools sampling dynamicFvMesh dynamicMesh \
           transportModels/incompressible transportModels/interfaceProperties \
           transportModels/twoPhaseMixture transportModels/immiscibleIncompressibleTwoPhaseMixture \
           TurbulenceModels/turbulenceModels TurbulenceModels/incompressible \
           sixDoFRigidBodyMotion functionObjects/forces fileFormats surfMesh; do
  includes="$includes -I$S/$lib/lnInclude"
done
libs="-lfiniteVolume -lfvOptions -lmeshTools -lsampling -ldynamicMesh -ldynamicFvMesh
      -lincompressibleTransportModels -linterfaceProperties
      -limmiscibleIncompressibleTwoPhaseMixture -lturbulenceModels
      -lincompressibleTurbulenceModels -lwaveModels -lsixDoFRigidBodyMotion -lforces
      -lOpenFOAM -ldl -lm"
# The interface's Crank–Nicolson flux on a moving mesh keeps the geometric conservation law
# (docs/openfoam-v1912.md, item 5): the copy of VoF/ interFoam compiles against makes the last
# step's flux relative to this step's mesh motion after v1912's blend, and keeps the last
# step's flux from the first step on.
KEEP='            phi.oldTime();'
GCL='        if (mesh.moving())\
        {\
            phiCN.ref() += (1.0 - cnCoeff)*(mesh.phi().oldTime() - mesh.phi());\
        }'
CN='isType<fv::CrankNicolsonDdtScheme<scalar>>(ddtAlpha))'
BLEND='phiCN = cnCoeff\*phi + (1.0 - cnCoeff)\*phi.oldTime();'
VOF=$OUT/VoF
rm -rf "$VOF" && cp -r "$SRC/applications/solvers/multiphase/VoF" "$VOF"
sed -i -e "/$CN/{n;a\\
$KEEP
}" -e "/$BLEND/a\\
$GCL" "$VOF/alphaEqn.H"
if [ "$(grep -c 'mesh.phi().oldTime() - mesh.phi()' "$VOF/alphaEqn.H")" != 1 ] ||
   [ "$(grep -c '^            phi.oldTime();$' "$VOF/alphaEqn.H")" != 1 ]; then
  echo "build_solver: alphaEqn.H has no Crank–Nicolson blend to correct" >&2
  exit 1
fi
# floatfoam's bodyVelocity (src/solver/) takes the body's velocity from the Laplacian's
# point-displacement condition, whose six-DoF motion v1912 keeps private: it is compiled again
# from Debian's source under the name bodySixDoFRigidBodyDisplacement, with an accessor (read
# through src/solver/bodyMotion.H by bodyVelocity and by couplingConvergence.H).
PPF=$SRC/src/sixDoFRigidBodyMotion/pointPatchFields/derived/sixDoFRigidBodyDisplacement
BODY=$OUT/bodyDisplacement
rm -rf "$BODY" && mkdir -p "$BODY"
for f in "$PPF"/sixDoFRigidBodyDisplacementPointPatchVectorField.[CH]; do
  sed -e 's/sixDoFRigidBodyDisplacement/bodySixDoFRigidBodyDisplacement/g' \
      -e '/TypeName("bodySixDoFRigidBodyDisplacement");/a\
    const sixDoFRigidBodyMotion\& motion() const { return motion_; }' \
      "$f" > "$BODY/body$(basename "$f" | sed 's/^s/S/')"
done
if [ "$(grep -c 'motion() const { return motion_; }' "$BODY"/*.H)" != 1 ]; then
  echo "build_solver: sixDoFRigidBodyDisplacement has no TypeName to add the accessor after" >&2
  exit 1
fi
# The gravity term with the density's jump at the free surface's height (src/solver/
# interfaceGravity.H, PIMPLE's `interfaceGravity`): interFoam's own folder is copied, its
# -ghf*snGrad(rho) in the momentum and pressure equations takes the face field that header returns.
APP=$OUT/interFoam
rm -rf "$APP" && mkdir -p "$APP"
cp "$SRC"/applications/solvers/multiphase/interFoam/*.[CH] "$APP/"
sed -i '/#include "fvcSmooth.H"/a\
#include "interfaceGravity.H"' "$APP/interFoam.C"
sed -i -e '0,/fvVectorMatrix UEqn/s//const surfaceScalarField ghInterface\
    (\
        floatfoamGravityGh(alpha1, gh, ghf, g, pimple.dict())\
    );\
\
    fvVectorMatrix UEqn/' -e 's/- ghf\*fvc::snGrad(rho)/- ghInterface*fvc::snGrad(rho)/' "$APP/UEqn.H"
sed -i 's/- ghf\*fvc::snGrad(rho)/- ghInterface*fvc::snGrad(rho)/' "$APP/pEqn.H"
if [ "$(cat "$APP/UEqn.H" "$APP/pEqn.H" | grep -c 'ghInterface\*fvc::snGrad(rho)')" != 2 ] ||
   [ "$(grep -c 'interfaceGravity.H' "$APP/interFoam.C")" != 1 ] ||
   [ "$(grep -c 'floatfoamGravityGh' "$APP/UEqn.H")" != 1 ]; then
  echo "build_solver: interFoam's gravity term is not where the edit expects it" >&2
  exit 1
fi
# The coupling's iterations end when the body's motion has converged (src/solver/
# couplingConvergence.H, PIMPLE's `couplingTolerance`): the mesh's motion in the PIMPLE loop is
# bracketed by the two calls that follow the body's velocities.
sed -i '/#include "interfaceGravity.H"/a\
#include "couplingConvergence.H"' "$APP/interFoam.C"
sed -i -e 's/^\( *\)mesh.update();$/\1floatfoamCoupling.before(mesh, pimple);\
\1mesh.update();\
\1floatfoamCoupling.after(mesh, pimple);/' \
  -e '/Starting time loop/i\
    Foam::floatfoamCouplingConvergence floatfoamCoupling;\
' -e '/Info<< "End\\n" << endl;/i\
    floatfoamCoupling.report(pimple);\
' "$APP/interFoam.C"
if [ "$(grep -c 'floatfoamCoupling\.' "$APP/interFoam.C")" != 3 ] ||
   [ "$(grep -c 'couplingConvergence.H' "$APP/interFoam.C")" != 1 ] ||
   [ "$(grep -c 'floatfoamCouplingConvergence floatfoamCoupling;' "$APP/interFoam.C")" != 1 ]
then
  echo "build_solver: interFoam's mesh motion is not where the edit expects it" >&2
  exit 1
fi
OBJECT_ID="$FLAGS $(cat "$VOF"/*.H "$APP"/*.[CH] "$BODY"/*.H src/solver/*.H | sha256sum |
  cut -c1-16)"
OFLAGS=$OUT/.interFoam.o.flags  # the flags and the VoF/ interFoam.o was compiled with
if [ ! -f "$OUT/interFoam.o" ] || [ "$(cat "$OFLAGS" 2>/dev/null)" != "$OBJECT_ID" ]; then
  app=$(realpath "$APP")
  own=$(realpath src/solver)
  body=$(realpath "$BODY")
  vof=$(realpath "$VOF")
  echo "build_solver: compiling interFoam with -fno-tree-vectorize (about a minute)"
  # shellcheck disable=SC2086  # word splitting of the flag lists is intended
  (cd "$app" && g++ $FLAGS -I. -I"$vof" -I"$own" -I"$body" -I"$S/transportModels" $includes \
     -c interFoam.C -o "$(realpath -m "$OLDPWD/$OUT/interFoam.o.tmp")")
  mv -f "$OUT/interFoam.o.tmp" "$OUT/interFoam.o" && echo "$OBJECT_ID" > "$OFLAGS"
fi
objects=("$OUT/interFoam.o")
for source in "$BODY"/*.C "${OWN[@]}"; do
  object=$OUT/$(basename "${source%.C}").o
  echo "build_solver: compiling $source"
  # shellcheck disable=SC2086
  g++ $FLAGS -I"$BODY" $includes -c "$source" -o "$object"
  objects+=("$object")
done
# shellcheck disable=SC2086
g++ -m64 "${objects[@]}" -L/lib -Xlinker --add-needed -Xlinker --no-as-needed $libs -o "$BIN.tmp"
mv -f "$BIN.tmp" "$BIN"  # whole or not at all: the driver runs whatever file is there
echo "$BUILT" > "$STAMP"
echo "build_solver: $BIN"
