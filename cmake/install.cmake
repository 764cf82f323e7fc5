# Where `cmake --install build --prefix P` puts things, all relative to P (so the same rules
# serve a prefix, the Debian package and a Python wheel's build), and the components they
# belong to (docs/install.md):
#
#   runtime      bin/gridrt, bin/gridrt-merge-tiles, the dlopen-ed modules (lib/gridrt/)
#   farm         bin/gridrt-farm and its Python package (share/gridrt/python/)
#   manual       share/man/man1/gridrt.1, made from `gridrt --help` at build time
#   completions  bash's and zsh's completions of gridrt's options
#   docs         README, LICENSE and docs/ in share/doc/gridrt
#
# The installed programs find what they need relative to their own location, never through
# the build or source tree, so the installed tree can be moved as a whole.
include(GNUInstallDirs)
# Installing and packaging take what is built and build nothing: `cpack` in a built tree
# then skips make's walk over every target (seconds), and an unbuilt file is an error.
set(CMAKE_SKIP_INSTALL_ALL_DEPENDENCY ON)

set(GRIDRT_INSTALL_MODULEDIR ${CMAKE_INSTALL_LIBDIR}/gridrt CACHE STRING
    "Where the dlopen-ed modules are installed, relative to the prefix")
set(GRIDRT_INSTALL_FARMDIR ${CMAKE_INSTALL_DATADIR}/gridrt/python CACHE STRING
    "Where the farm's Python package is installed, relative to the prefix")
set(GRIDRT_INSTALL_DOCDIR ${CMAKE_INSTALL_DATAROOTDIR}/doc/gridrt CACHE STRING
    "Where README, LICENSE and docs/ are installed, relative to the prefix")
set(GRIDRT_INSTALL_BASHDIR ${CMAKE_INSTALL_DATAROOTDIR}/bash-completion/completions CACHE
    STRING "Where bash's completion of gridrt is installed (bash-completion loads it there)")
# Debian's zsh reads /usr/share/zsh/vendor-completions (the package's place) and
# /usr/local/share/zsh/site-functions; zsh built from source reads site-functions.
if(EXISTS /etc/debian_version)
  set(_zsh_dir vendor-completions)
else()
  set(_zsh_dir site-functions)
endif()
set(GRIDRT_INSTALL_ZSHDIR ${CMAKE_INSTALL_DATAROOTDIR}/zsh/${_zsh_dir} CACHE STRING
    "Where zsh's completion of gridrt (_gridrt) is installed")
foreach(dir CMAKE_INSTALL_BINDIR GRIDRT_INSTALL_MODULEDIR GRIDRT_INSTALL_FARMDIR)
  if(IS_ABSOLUTE "${${dir}}")
    message(FATAL_ERROR "${dir} must be relative to the prefix (the installed programs find "
                        "each other relative to their own place), got '${${dir}}'")
  endif()
endforeach()
# The modules' folder as seen from the installed executable (../lib/gridrt): the loaders
# take it as a compile definition and look there after the executable's own folder.
file(RELATIVE_PATH GRIDRT_MODULE_DIR_FROM_BIN /prefix/${CMAKE_INSTALL_BINDIR}
     /prefix/${GRIDRT_INSTALL_MODULEDIR})
file(RELATIVE_PATH GRIDRT_FARM_DIR_FROM_BIN /prefix/${CMAKE_INSTALL_BINDIR}
     /prefix/${GRIDRT_INSTALL_FARMDIR})

# gridrt_install_module(TARGET): installs the MODULE library TARGET where an installed
# gridrt finds it (GRIDRT_MODULE_DIR_FROM_BIN from the executable's folder), in the runtime
# component. Its loader looks there through host/core/module_search.h.
function(gridrt_install_module target)
  get_target_property(type ${target} TYPE)
  if(NOT type STREQUAL "MODULE_LIBRARY")
    message(FATAL_ERROR "gridrt_install_module(${target}): a MODULE library, got ${type}")
  endif()
  install(TARGETS ${target} LIBRARY DESTINATION ${GRIDRT_INSTALL_MODULEDIR} COMPONENT runtime)
endfunction()

# gridrt_install_program(TARGET): an executable into bin/, in the runtime component.
function(gridrt_install_program target)
  install(TARGETS ${target} RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR} COMPONENT runtime)
endfunction()
