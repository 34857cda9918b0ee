// Forwards to the public header (verifier.cpp includes this name).
#pragma once

#include "oblique/verify/child_process.h"
