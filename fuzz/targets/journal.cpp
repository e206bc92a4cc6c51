// The recorder's journal (dataset/measurement_journal.hpp): a killed recorder leaves a torn tail, a full disk or a
// damaged file anything; parsed as a respawned recorder reads it (the valid prefix), then its records re-encoded
// and parsed again (the same prefix must come back).
#include <stdexcept>
#include <string_view>

#include "../fuzz_target.hpp"
#include "cosmo/dataset/measurement_journal.hpp"

using namespace cosmo;

COSMO_FUZZ_TARGET(journal) {
  const std::string_view bytes(reinterpret_cast<const char*>(data), size);
  const dataset::JournalContents c = dataset::parseJournal(bytes, "input.journal");
  std::string again = dataset::encodeJournalHeader(c.header);
  for (const auto& r : c.records) again += dataset::encodeJournalRecord(r);
  const dataset::JournalContents d = dataset::parseJournal(again, "re-encoded");
  if (d.records.size() != c.records.size() || !d.tail_error.empty())
    throw std::logic_error("journal: the re-encoded valid prefix does not read back");
}
