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
