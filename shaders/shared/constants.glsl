// Shared by GLSL and C++ (common/shading/shared_shading.hpp). Keep to the common subset.
const float CUPOLA_PI = 3.14159265358979;
