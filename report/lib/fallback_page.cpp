// The pages used when Node.js/npm were not found at build time: no plots, no
// 3D; each says so and shows the embedded run (or campaign) data as text.
#include <cstddef>

namespace report {
namespace detail {
extern const char kPagePrefix[];
extern const std::size_t kPagePrefixSize;
extern const char kPageSuffix[];
extern const std::size_t kPageSuffixSize;
extern const char kMcPagePrefix[];
extern const std::size_t kMcPagePrefixSize;
extern const char kMcPageSuffix[];
extern const std::size_t kMcPageSuffixSize;
extern const bool kHasBundle;

// both pages end alike: the data element closed, then shown as text
#define KESTREL_FALLBACK_SUFFIX                                                                    \
  "</script>\n<pre id=\"raw\"></pre>\n"                                                            \
  "<script>document.getElementById('raw').textContent=document.getElementById('kestrel-data').textContent;</script>\n" \
  "</body></html>\n"

const char kPagePrefix[] = R"KRPT(<!DOCTYPE html>
<html lang="en"><head><meta charset="utf-8"><title>Kestrel run report (data only)</title></head>
<body><h1>Kestrel run report</h1>
<p>This build of Kestrel had no Node.js/npm, so the report's plots and 3D replay were not built
(scripts/install-deps.sh host installs them). The run data follows.</p>
<script id="kestrel-data" type="application/json">)KRPT";
const std::size_t kPagePrefixSize = sizeof(kPagePrefix) - 1;
const char kPageSuffix[] = KESTREL_FALLBACK_SUFFIX;
const std::size_t kPageSuffixSize = sizeof(kPageSuffix) - 1;

const char kMcPagePrefix[] = R"KRPT(<!DOCTYPE html>
<html lang="en"><head><meta charset="utf-8"><title>Kestrel Monte Carlo report (data only)</title></head>
<body><h1>Kestrel Monte Carlo report</h1>
<p>This build of Kestrel had no Node.js/npm, so the report's plots and tables were not built
(scripts/install-deps.sh host installs them). The campaign data follows.</p>
<script id="kestrel-data" type="application/json">)KRPT";
const std::size_t kMcPagePrefixSize = sizeof(kMcPagePrefix) - 1;
const char kMcPageSuffix[] = KESTREL_FALLBACK_SUFFIX;
const std::size_t kMcPageSuffixSize = sizeof(kMcPageSuffix) - 1;

const bool kHasBundle = false;
extern const char kLivePage[];
extern const std::size_t kLivePageSize;
const char kLivePage[] = R"KRPT(<!DOCTYPE html>
<html lang="en"><head><meta charset="utf-8"><title>Kestrel live view (no page)</title></head>
<body><h1>Kestrel live view</h1>
<p>This build of Kestrel had no Node.js/npm, so the live page was not built (scripts/install-deps.sh host
installs them). The API answers at /api/info, /api/frames and /api/command (docs/live.md).</p>
</body></html>
)KRPT";
const std::size_t kLivePageSize = sizeof(kLivePage) - 1;
}  // namespace detail
}  // namespace report
