# Every dependency is a Debian package (scripts/install-deps.sh); nothing is downloaded here.
find_package(Threads REQUIRED)
find_package(nlohmann_json 3.10 REQUIRED)
find_package(Eigen3 3.4 REQUIRED NO_MODULE)
find_package(fmt REQUIRED)
find_package(FastFloat REQUIRED)
find_package(tomlplusplus REQUIRED)
find_package(CLI11 REQUIRED)
find_package(Boost 1.74 REQUIRED)
# The results archive: SQLite embedded, PostgreSQL (libpq) for a lab's shared server.
find_package(SQLite3 REQUIRED)
find_package(PostgreSQL REQUIRED)
# SHA-256 of records and campaigns (core/sha256.cc): OpenSSL's libcrypto, with the processor's SHA
# extensions.
find_package(OpenSSL REQUIRED COMPONENTS Crypto)
# Lab record formats (issue 21): HDF5 through its C API, MATLAB .mat (v5, v7, v7.3) through matio.
# FindHDF5 test-compiles a C program: the C language is enabled for it (no C sources are built).
enable_language(C)
find_package(HDF5 REQUIRED COMPONENTS C)
find_package(PkgConfig REQUIRED)
pkg_check_modules(MATIO REQUIRED IMPORTED_TARGET matio)
# FFTW (double precision) for the Welch power spectral density of the Allan analysis (issue 19).
pkg_check_modules(FFTW3 REQUIRED IMPORTED_TARGET fftw3)
# zlib: the check of a compressed MAT variable's headers before matio reads it.
find_package(ZLIB REQUIRED)
# cpp-httplib for `inertest serve` (issue 17). Debian's is a compiled library whose pkg-config file
# carries the feature macros (OpenSSL, zlib, Brotli) it was built with: every source including
# httplib.h must define the same ones, since they change its classes' layout.
pkg_check_modules(HTTPLIB REQUIRED IMPORTED_TARGET cpp-httplib)
