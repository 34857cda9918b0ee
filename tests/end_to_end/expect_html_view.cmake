cmake_minimum_required(VERSION 3.25)
# cmake -DPAGE=report.html -P expect_html_view.cmake: the browser check of one page
# (html_view_check.cmake); "browser check skipped" where Chromium is not installed.
include(${CMAKE_CURRENT_LIST_DIR}/html_view_check.cmake)
check_html_view("${PAGE}")
