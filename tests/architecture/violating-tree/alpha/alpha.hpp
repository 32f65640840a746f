// Fixture of the module dependency check: module alpha includes beta without declaring it.
#pragma once
#include "kaboum/beta/beta.hpp"
