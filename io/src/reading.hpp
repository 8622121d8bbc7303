// The point and face readers' shared parts (point_io.cpp, face_io.cpp), one header each: errors, the line and
// byte source, tokens and correctly rounded numbers, the OFF text, and the PLY header with its binary and
// ASCII vertex records.  Internal to io/.
#pragma once

#include "line_source.hpp"
#include "off_text.hpp"
#include "ply_ascii.hpp"
#include "ply_binary.hpp"
#include "ply_header.hpp"
#include "read_failures.hpp"
#include "text_numbers.hpp"

// point_io.cpp checks double coordinates against the fast predicates' range (in_fast_exact_range).
#include "cudahull/predicates.hpp"
