// A user's program built against the installed asperity package.
#include <asperity/contact/material.hpp>
#include <cstdio>

int main() {
  using asperity::contact::Material;
  const Material steel{.E = 207e9, .nu = 0.3, .G = 82.7e9, .H = 6.83e9};
  const auto pair = asperity::contact::ContactPair::combine(steel, steel, 2.5e-3);
  std::printf("omega_c = %.3g um\n", pair.critical().omega_c * 1e6);
  return 0;
}
