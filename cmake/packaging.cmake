# The Debian package: `cpack -G DEB` in the build folder packs what `cmake --install` puts
# under /usr (cmake/install.cmake's components but the Python module's), with dependencies
# from the shared libraries the programs and the image module link (dpkg-shlibdeps) and the
# farm's Python ones declared (docs/install.md).
set(CPACK_GENERATOR DEB)
set(CPACK_PACKAGE_NAME gridrt)
set(CPACK_PACKAGE_VERSION ${PROJECT_VERSION})
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY
    "Whitted-style ray tracer on OpenCL with the GridRT parallel architecture")
set(CPACK_PACKAGE_DESCRIPTION
    "Renders glTF 2.0, OBJ, PLY and STL scenes with shadows, reflection and refraction to PNG,
JPEG or EXR on any OpenCL 1.2 device: the scene split into voxels, each non-empty voxel a
processing element, a two-phase reduction keeping each ray's closest hit. With
gridrt-merge-tiles and gridrt-farm, which renders a job's tiles and frames on a Dask cluster.")
set(CPACK_PACKAGING_INSTALL_PREFIX /usr)
set(CPACK_STRIP_FILES ON)
set(CPACK_COMPONENTS_ALL runtime farm manual completions docs)
set(CPACK_DEB_COMPONENT_INSTALL ON)
set(CPACK_COMPONENTS_GROUPING ALL_COMPONENTS_IN_ONE)  # one package, gridrt_VERSION_ARCH.deb
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)
set(GRIDRT_PACKAGE_MAINTAINER "GridRT developers <gridrt@localhost>" CACHE STRING
    "The Debian package's Maintainer field")
set(CPACK_DEBIAN_PACKAGE_MAINTAINER "${GRIDRT_PACKAGE_MAINTAINER}")
set(CPACK_DEBIAN_PACKAGE_SECTION graphics)
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)
# The farm runs on Debian's python3 with Dask distributed; a device needs an OpenCL driver
# (the ICD loader alone comes from shlibdeps): PoCL's CPU device, or any other.
set(CPACK_DEBIAN_PACKAGE_DEPENDS "python3, python3-distributed")
set(CPACK_DEBIAN_PACKAGE_RECOMMENDS "pocl-opencl-icd | opencl-icd")
if(GRIDRT_NATIVE)
  message(STATUS "GRIDRT_NATIVE is on: a package built here runs only on CPUs like this one "
                 "(configure with -DGRIDRT_NATIVE=OFF to ship it)")
endif()
include(CPack)
