cmake_minimum_required(VERSION 3.25)
# Runs `oblique verify --consumers KINDS` on a program and checks the outcome:
#   cmake -DOBLIQUE=... -DIMPL=... -DKINDS=a,b -DEXIT=0|1 [-DPROPERTY=name -DPICTURES=0|1
#         -DRIGHT=command -DCAUSE=name] [-DARGS="--time-limit;5"] -DREPORTS=dir
#         -P expect_verify_consumers.cmake
# EXIT 1 also requires the report (Markdown and JSON) of PROPERTY (or of one of "a|b", for a
# mistake that breaks two properties, whichever the round judges first), its replay commands, its
# pictures (of the case's volume when PICTURES is 1, else of the pass's cameras and planes), its
# round's picks shrunk (the report says so), and its --replay to be violated again by IMPL and to
# hold for RIGHT; with CAUSE, the output and the report name that likely cause
# (mistakes/consumer_mistakes.h).
file(REMOVE_RECURSE "${REPORTS}")
execute_process(COMMAND "${OBLIQUE}" verify --consumers "${KINDS}" --impl "${IMPL}"
                        --report-dir "${REPORTS}" --quiet ${ARGS}
                RESULT_VARIABLE result OUTPUT_VARIABLE output ERROR_VARIABLE errors)
message(STATUS "${output}${errors}")
if(NOT result EQUAL EXIT)
  message(FATAL_ERROR "oblique verify exited with ${result}, expected ${EXIT}")
endif()
if(EXIT EQUAL 0)
  if(NOT output MATCHES "no violation in [1-9][0-9]* answers judged")
    message(FATAL_ERROR "a pass must say how many answers were judged")
  endif()
  return()
endif()
string(REPLACE "|" ";" properties "${PROPERTY}")
foreach(candidate ${properties})
  if(EXISTS "${REPORTS}/verify-consumer-${candidate}.json")
    set(PROPERTY ${candidate})
  endif()
endforeach()
set(stem "${REPORTS}/verify-consumer-${PROPERTY}")
foreach(file "${stem}.md" "${stem}.json")
  if(NOT EXISTS "${file}")
    message(FATAL_ERROR "no report ${file}")
  endif()
endforeach()
file(READ "${stem}.json" json)
string(JSON check GET "${json}" check)
if(NOT check STREQUAL PROPERTY)
  message(FATAL_ERROR "the report is about ${check}, not ${PROPERTY}")
endif()
file(READ "${stem}.md" md)
if(CAUSE)
  if(NOT "${output}${errors}" MATCHES "likely cause: ${CAUSE}")
    message(FATAL_ERROR "the output does not name the likely cause ${CAUSE}")
  endif()
  if(NOT md MATCHES "## Likely cause\n\n\\*\\*`${CAUSE}`")
    message(FATAL_ERROR "the report does not name the likely cause ${CAUSE}")
  endif()
endif()
foreach(part "violates \\*\\*${PROPERTY}\\*\\*" "its picks (shrunk in [0-9]+ steps|already at their smallest)" "## The inputs"
             "## The exchange" "## Replay" "verify --replay")
  if(NOT md MATCHES "${part}")
    message(FATAL_ERROR "the report has no '${part}'")
  endif()
endforeach()
if(NOT EXISTS "${stem}.views.dat" OR NOT md MATCHES "## Pictures")
  message(FATAL_ERROR "the report has no pictures (${stem}.views.dat)")
endif()
if(PICTURES AND NOT md MATCHES "The case in eye space")
  message(FATAL_ERROR "the report's pictures are not of the case's volume")
endif()
if(NOT PICTURES AND NOT md MATCHES "what the finding is about")
  message(FATAL_ERROR "the report's pictures are not of the pass's cameras and planes")
endif()
execute_process(COMMAND "${OBLIQUE}" verify --replay "${stem}.json" --impl "${IMPL}"
                RESULT_VARIABLE again OUTPUT_VARIABLE replayed ERROR_VARIABLE replay_errors)
if(NOT again EQUAL 1 OR NOT replayed MATCHES "${PROPERTY} violated")
  message(FATAL_ERROR "the replay gave ${again}, not the violation: ${replayed}${replay_errors}")
endif()
if(RIGHT)
  execute_process(COMMAND "${OBLIQUE}" verify --replay "${stem}.json" --impl "${RIGHT}"
                  RESULT_VARIABLE right OUTPUT_VARIABLE right_output ERROR_VARIABLE right_errors)
  if(NOT right EQUAL 0)
    message(FATAL_ERROR "the right program does not hold on the replay (${right}): "
                        "${right_output}${right_errors}")
  endif()
endif()
