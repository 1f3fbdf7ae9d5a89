# The bullet solver's part of the build, included by the top CMakeLists.txt (its loop over
# solvers/): built into poundbench_core when its library is found, left out without it.
# Debian's libbullet-dev ships single (bullet) and double (bullet-float64) precision
# builds with the same symbols; one program can link only one of them.
pkg_check_modules(BULLET IMPORTED_TARGET bullet)
poundbench_engine(BULLET BULLET_FOUND PUBLIC PkgConfig::BULLET)
