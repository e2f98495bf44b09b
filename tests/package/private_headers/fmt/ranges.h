// Stands in for a private dependency of asperity on the include path of the consumer
// tests (tests/package): a public header that includes it fails to compile.
#error "a public asperity header includes <fmt/ranges.h>, a private dependency"
