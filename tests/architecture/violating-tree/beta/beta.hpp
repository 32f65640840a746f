// Fixture of the module dependency check: a module with no dependencies.
#pragma once
