# The documented install step works: `cmake --install BUILD --prefix PREFIX` puts the module into
# PREFIX's user site-packages, where the interpreter imports it with no PYTHONPATH (PYTHONUSERBASE
# stands for ~/.local here).
file(REMOVE_RECURSE ${PREFIX})
execute_process(COMMAND ${CMAKE_COMMAND} --install ${BINARY_DIR} --prefix ${PREFIX} RESULT_VARIABLE status OUTPUT_QUIET)
if(status)
  message(FATAL_ERROR "cmake --install failed: ${status}")
endif()
execute_process(
  COMMAND ${CMAKE_COMMAND} -E env --unset=PYTHONPATH PYTHONUSERBASE=${PREFIX}
          ${PYTHON} -c "import inertest, sys; assert inertest.__file__.startswith(sys.argv[1]), inertest.__file__; print(inertest.__file__)" ${PREFIX}
  WORKING_DIRECTORY ${PREFIX}
  RESULT_VARIABLE status)
if(status)
  message(FATAL_ERROR "import inertest failed after the install: ${status}")
endif()
