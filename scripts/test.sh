#!/usr/bin/env bash
# Sets up (scripts/setup.sh), builds with warnings as errors, and runs every test: unit,
# verification and regression; then the unit and verification tests again under AddressSanitizer
# and UndefinedBehaviorSanitizer (CMakePresets.json "asan-ubsan", build-asan/), but for the few
# long specimen runs, which the first pass covers. RCDEM_SKIP_SANITIZERS=1 skips the second pass.
# Between them, the distributed run's build and tests.
set -euo pipefail
cd "$(dirname "$0")/.."
RCDEM_SETUP_MPI=1 RCDEM_WERROR=ON bash scripts/setup.sh
OMP_WAIT_POLICY=${OMP_WAIT_POLICY:-passive} ctest --test-dir "${BUILD_DIR:-build}" --output-on-failure -j "$(nproc)" "$@"
# The distributed run (CMakePresets.json "mpi", build-mpi/: the binary alone): the same bits as
# one process on 2 and 3 ranks, resumed across rank counts, failures (label mpi).
# RCDEM_SKIP_MPI=1 skips it.
if [ "${RCDEM_SKIP_MPI:-0}" != 1 ]; then
  cmake --preset mpi -DRCDEM_WERROR=ON >/dev/null
  cmake --build build-mpi -j "$(nproc)" --target rcdem
  OMP_WAIT_POLICY=${OMP_WAIT_POLICY:-passive} ctest --test-dir build-mpi --output-on-failure -L mpi
fi
[ "${RCDEM_SKIP_SANITIZERS:-0}" = 1 ] && exit 0
# Minutes each under the sanitizers, seconds in the first pass.
# The held contacts' and the point counters' runs through a peak keep one test each here (their
# strain energy, the crack record), the thread tuner's bits the first pass.
LONG='StrainGauges.ElasticModulusDoesNotDependOnCubeSize|ElasticCondensation.(Tension|Compression)RunMatchesThePointLoopThroughDamage|CriticalTimeStep.(ReinforcedCube|Stable|Cundall)|ExponentialSoftening.BoxInTension|Checkpoint.StateDoesNotDependOnThreadCount|BarStatics.Cantilever|HeldContacts.(SameResultsAsVisiting|SameBitsForAnyThreadCount|AHeldContactsForceMoments)|PointCounters.(StrainEnergyKeptByTheStep|KeptByTheStepEqualACount)|ThreadCountTuner.ACountThatChangesBetweenSteps|ScaleInvariance.CoarserParticles'
cmake --preset asan-ubsan -DRCDEM_WERROR=ON >/dev/null
cmake --build build-asan -j "$(nproc)" --target rcdem_unit_tests rcdem_verification_tests
OMP_WAIT_POLICY=${OMP_WAIT_POLICY:-passive} ctest --test-dir build-asan --output-on-failure \
  -j "$(nproc)" -L 'unit|verification' -E "$LONG"
