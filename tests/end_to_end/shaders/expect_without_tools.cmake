# oblique verify --shader on an HLSL file with no glslang on PATH: exit 2, saying what to install.
#   cmake -DOBLIQUE=... -DSHADER=file.hlsl -DREPORTS=dir -P expect_without_tools.cmake
set(ENV{PATH} "/nonexistent")
execute_process(COMMAND "${OBLIQUE}" verify --consumers view_position --shader "${SHADER}"
                        --time-limit 1 --report-dir "${REPORTS}"
                RESULT_VARIABLE result OUTPUT_VARIABLE output ERROR_VARIABLE output)
message(STATUS "${output}")
if(NOT result EQUAL 2 OR NOT output MATCHES "install glslang-tools spirv-cross")
  message(FATAL_ERROR "exit ${result}, expected 2 and what to install")
endif()
