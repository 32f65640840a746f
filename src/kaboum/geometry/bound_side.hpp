// Which side of the original surface a single-sided approximation lies on (thesis §4.2.2).
#pragma once

namespace kaboum::geometry {

// Outer: the approximation encloses the original. Inner: the original encloses the approximation.
enum class BoundSide { Outer, Inner };

}  // namespace kaboum::geometry
