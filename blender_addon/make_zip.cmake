# Writes the add-on's zip: cmake -DSOURCE=DIR -DLIBRARY=FILE -DSTAGING=DIR
# -DOUTPUT=FILE.zip -P make_zip.cmake. The zip holds one folder,
# shafts_blender/, with the package's files (no __pycache__, no *_test.py)
# and libshafts.so copied next to shafts.py (the real file, not a link), with
# the image plugin libshafts_oiio.so beside it when -DPLUGIN=FILE names one.
file(REMOVE_RECURSE "${STAGING}")
file(GLOB_RECURSE files RELATIVE "${SOURCE}" "${SOURCE}/*")
foreach(f ${files})
  if(f MATCHES "(^|/)__pycache__/" OR f MATCHES "_test\\.py$" OR f MATCHES "\\.pyc$")
    continue()
  endif()
  get_filename_component(dir "${f}" DIRECTORY)
  file(COPY "${SOURCE}/${f}" DESTINATION "${STAGING}/shafts_blender/${dir}")
endforeach()
get_filename_component(libname "${LIBRARY}" NAME)
file(COPY "${LIBRARY}" DESTINATION "${STAGING}")
file(RENAME "${STAGING}/${libname}" "${STAGING}/shafts_blender/libshafts.so")
if(PLUGIN)
  file(COPY "${PLUGIN}" DESTINATION "${STAGING}/shafts_blender")
endif()
file(REMOVE "${OUTPUT}")
execute_process(COMMAND "${CMAKE_COMMAND}" -E tar cf "${OUTPUT}" --format=zip shafts_blender
                WORKING_DIRECTORY "${STAGING}" RESULT_VARIABLE status)
if(NOT status EQUAL 0)
  message(FATAL_ERROR "make_zip.cmake: could not write ${OUTPUT}")
endif()
