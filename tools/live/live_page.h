// The browser page of the live server (docs/live.md, 'In a browser'): GET / gives a page
// that lists the channels and plots chosen fields live from the same WebSocket, decoding
// the CDR of mechsim's structs itself (page/live.js); uPlot (MIT, vendored from npm under
// page/vendor/) draws. Everything is compiled in: no file and no CDN is needed at run time.
#pragma once

#include <string>

#include "ws_endpoint.h"

namespace mechsim::live {

// The page's files by path ("/", "/live.js", ...); 404 for any other path.
HttpReply page_reply(const std::string& path);

}  // namespace mechsim::live
