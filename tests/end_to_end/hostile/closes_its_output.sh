#!/bin/sh
# A program that closes its standard output and goes on running: it answers nothing.
exec >&-
exec sleep 10
