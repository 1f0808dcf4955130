// Integrity of the stage cache files: a file records which stage and key it was made for and a
// manifest of its contents (every group, dataset and attribute with its type, shape and a digest
// of its bytes), itself under a digest, and a record beside it (<file>.digest) holds the digest
// of the whole file's bytes; a file is reused only when all of that still holds. The bytes are
// checked first, so that HDF5 never reads a damaged file.
//
// What it guards against: a file damaged on the disk or by hand (values overwritten, a dataset
// deleted), a file of another scene or stage put in its place (swapped, copied), a file cut
// short. It is a check against accidents (64-bit FNV-1a), not a security measure.
#pragma once

#include "driver/h5_file.h"

#include <string>

namespace gearkit
{
/// The digest (64-bit FNV-1a over 8-byte words, 16 hex digits) of a text: cache files' records
/// and the stages' cache keys.
std::string
text_digest(const std::string &text);

/// Records in the root of `file` (being written, before commit) the stage, the key and the
/// manifest of everything in it, with the manifest's digest.
void
seal_cache_file(const H5File &file, const std::string &stage, const std::string &key);

/// Records the size and digest of the committed file's bytes beside it (<path>.digest), so
/// that a damaged or replaced file is recognised before HDF5 reads a byte of it.
void
record_cache_digest(const std::string &path);

/// What keeps the cache file at `path` from being reused for `stage` with `key`: empty when its
/// bytes are those recorded beside it, it names this stage and key, holds exactly what its manifest
/// lists with the same digests, and its floating-point datasets are finite (results never hold
/// NaN or infinities: H5Group::write refuses them). Else one line saying what is wrong (for the
/// log).
std::string
cache_file_problem(const std::string &path, const std::string &stage, const std::string &key);
} // namespace gearkit
