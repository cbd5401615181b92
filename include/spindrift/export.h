// spindrift public API: SPINDRIFT_API marks what the library exports. The
// library is compiled with hidden symbol visibility (-fvisibility=hidden), so
// a shared libspindrift.so exports exactly the declarations that carry this
// mark and nothing of src/. In a static library the mark changes nothing.
#pragma once

#if defined(__GNUC__) || defined(__clang__)
#define SPINDRIFT_API __attribute__((visibility("default")))
#else
#define SPINDRIFT_API
#endif
