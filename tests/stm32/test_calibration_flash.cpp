// SPDX-License-Identifier: Apache-2.0
// Calibration in flash on the flash model (flash_model.hpp): the contract-3 store
// (calibration_flash.hpp) over the journal (palp/fw/flash_journal.hpp) and the STM32 flash driver
// (flash_driver.hpp) — slot placement and layout, register use, non-blocking polls, option-byte
// and write-protection failures, the ECC NMI hook, every rejection reason, migration of a v1
// block. Power cuts: test_calibration_flash_power_cut.cpp.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <vector>

#include "calibration_flash_support.hpp"
#include "palp/protocol/crc32.hpp"

namespace palp::stm32::test {
namespace {

using fw::SlotStatus;

constexpr std::uint32_t kSlotA = 0x0807'F000;
constexpr std::uint32_t kSlotB = 0x0807'F800;

std::uint32_t word_at(FlashModel& m, std::uint32_t address) {
  return static_cast<std::uint32_t>(m.at(address & ~7u).value >> ((address & 4u) ? 32 : 0));
}

TEST(Stm32CalibrationFlash, SlotsAreTheLastTwoPagesOfBank2) {
  EXPECT_EQ(kCalibrationJournalLayout.slot_address[0], kSlotA);  // bank 2 page 126
  EXPECT_EQ(kCalibrationJournalLayout.slot_address[1], kSlotB);  // bank 2 page 127
  EXPECT_EQ(flash::kStorageEnd, 0x0808'0000u);                   // the end of the 512 KB
}

TEST(Stm32CalibrationFlash, BlankFlashReadsAsErasedAndTheCoreSeesBlank) {
  FlashModel model;
  const Boot b = boot(model);
  EXPECT_EQ(b.bytes, erased_read());
  EXPECT_EQ(fw::load_calibration(b.bytes).status, fw::CalibrationStatus::blank);
  EXPECT_EQ(b.scan.newest, -1);
  EXPECT_EQ(b.scan.slots[0].status, SlotStatus::erased);
  EXPECT_EQ(b.scan.slots[1].status, SlotStatus::erased);
  EXPECT_TRUE(model.violations().empty());
}

TEST(Stm32CalibrationFlash, AWrittenBlockReadsBackExactlyAfterAReset) {
  FlashModel model;
  ASSERT_TRUE(commit(model, calibration_bytes(1)));
  const Boot b = boot(model);
  EXPECT_EQ(b.bytes, calibration_bytes(1));
  const fw::CalibrationLoad load = fw::load_calibration(b.bytes);
  EXPECT_EQ(load.status, fw::CalibrationStatus::ok);
  EXPECT_EQ(load.data.spring_k_N_per_m, 41.0f);
  EXPECT_TRUE(model.violations().empty());
}

TEST(Stm32CalibrationFlash, CommitsAlternateSlotsWithRisingSequencesKeepingTheOlderBlock) {
  FlashModel model;
  for (int n = 1; n <= 3; ++n) ASSERT_TRUE(commit(model, calibration_bytes(n)));
  const Boot b = boot(model);
  EXPECT_EQ(b.bytes, calibration_bytes(3));
  EXPECT_EQ(b.scan.newest, 0);
  EXPECT_EQ(b.scan.slots[0].status, SlotStatus::valid);
  EXPECT_EQ(b.scan.slots[0].sequence, 3u);
  EXPECT_EQ(b.scan.slots[1].status, SlotStatus::valid);  // block 2 kept until the next commit
  EXPECT_EQ(b.scan.slots[1].sequence, 2u);
  std::vector<std::uint32_t> erased;
  for (const FlashModel::Operation& op : model.operations())
    if (op.erase) erased.push_back(op.address);
  EXPECT_EQ(erased, (std::vector<std::uint32_t>{kSlotA, kSlotB, kSlotA}));
}

TEST(Stm32CalibrationFlash, SlotHoldsHeaderBlockCrcAndMarkerAsDocumented) {
  FlashModel model;
  const std::vector<std::uint8_t> block = calibration_bytes(7);
  ASSERT_TRUE(commit(model, block));
  EXPECT_EQ(word_at(model, kSlotA), 0x4C4E4A50u);            // "PJNL"
  EXPECT_EQ(word_at(model, kSlotA + 4), 1u | (208u << 16));  // layout 1, length 208
  EXPECT_EQ(word_at(model, kSlotA + 8), 1u);                 // sequence 1
  EXPECT_EQ(word_at(model, kSlotA + 12), 0u);
  std::vector<std::uint8_t> slot(16 + 208);
  for (std::size_t k = 0; k < slot.size(); k += 4) {
    const std::uint32_t w = word_at(model, kSlotA + static_cast<std::uint32_t>(k));
    std::memcpy(&slot[k], &w, 4);  // the host is little-endian like the part
  }
  EXPECT_TRUE(std::equal(block.begin(), block.end(), slot.begin() + 16));
  EXPECT_EQ(model.at(kSlotA + 16 + 208).value, proto::crc32(slot.data(), slot.size()));
  EXPECT_EQ(model.at(kSlotB - 8).value, 0x54494D43504C4150ull);  // "PALPCMIT" at the page end
  for (std::uint32_t a = kSlotA + 16 + 208 + 8; a < kSlotB - 8; a += 8)
    ASSERT_EQ(model.at(a).value, FlashModel::kErased) << std::hex << a;
}

TEST(Stm32CalibrationFlash, EraseThenEveryDoubleWordOnceInAddressOrderWithTheMarkerLast) {
  FlashModel model;
  ASSERT_TRUE(commit(model, calibration_bytes(1)));
  const std::vector<FlashModel::Operation>& ops = model.operations();
  ASSERT_EQ(ops.size(), CalibrationStore::Journal::operations_for(208));
  ASSERT_EQ(ops.size(), 31u);  // 1 erase + header 2 + block 26 + CRC 1 + marker 1
  EXPECT_TRUE(ops[0].erase);
  EXPECT_EQ(ops[0].address, kSlotA);
  for (std::size_t k = 1; k < ops.size(); ++k) {
    EXPECT_FALSE(ops[k].erase);
    if (k > 1) {
      EXPECT_GT(ops[k].address, ops[k - 1].address);
    }
  }
  EXPECT_EQ(ops.back().address, kSlotB - 8);
}

TEST(Stm32CalibrationFlash, DriverUnlocksErasesBank2WithCachesHandledAndLocksAgain) {
  FlashModel model;
  ASSERT_TRUE(commit(model, calibration_bytes(1)));
  EXPECT_TRUE(model.violations().empty());  // keys in order, CR never written locked or BSY
  EXPECT_EQ(flash::Cr::LOCK.decode(model.cr()), 1u);
  EXPECT_EQ(model.cr() & (flash::Cr::PG.mask() | flash::Cr::PER.mask()), 0u);
  EXPECT_EQ(model.sr(), 0u);  // EOP and errors cleared
  // The D-cache goes off before the erase and everything is back as it was after it.
  const std::vector<std::uint32_t>& acr = model.acr_writes();
  ASSERT_FALSE(acr.empty());
  EXPECT_EQ(flash::Acr::DCEN.decode(acr.front()), 0u);
  bool icache_reset = false, dcache_reset = false;
  for (std::uint32_t w : acr) {
    icache_reset |= flash::Acr::ICRST.decode(w) == 1 && flash::Acr::ICEN.decode(w) == 0;
    dcache_reset |= flash::Acr::DCRST.decode(w) == 1 && flash::Acr::DCEN.decode(w) == 0;
  }
  EXPECT_TRUE(icache_reset);
  EXPECT_TRUE(dcache_reset);
  EXPECT_EQ(model.acr(), 0x0004'0601u);  // the reset value again: ICEN, DCEN on, resets clear
}

TEST(Stm32CalibrationFlash, EveryPollStartsAtMostOneFlashStepWithBoundedRegisterAccesses) {
  FlashModel model;
  CalibrationStore store(model);
  const std::vector<std::uint8_t> block = calibration_bytes(1);
  ASSERT_TRUE(store.begin_write(block.data(), block.size()));
  std::size_t polls = 0, busy_polls = 0;
  std::uint64_t most_accesses = 0;
  while (true) {
    const std::size_t ops_before = model.operations().size();
    const std::uint64_t accesses_before = model.accesses();
    const fw::CommitState s = store.poll();
    ++polls;
    EXPECT_LE(model.operations().size() - ops_before, 1u);
    if (s == fw::CommitState::done) break;  // (the last poll reads the slot back)
    most_accesses = std::max(most_accesses, model.accesses() - accesses_before);
    if (model.operations().size() == ops_before) ++busy_polls;
    ASSERT_TRUE(s == fw::CommitState::erasing || s == fw::CommitState::programming);
    ASSERT_LT(polls, 1000u);
  }
  EXPECT_LE(most_accesses, 40u);  // flags, CR, ACR caches after the erase, a program's 2 words
  // every BSY the model shows (erase 3, each program 1) is seen, none waited on
  EXPECT_EQ(busy_polls, 3u + 30u);
  EXPECT_EQ(boot(model).bytes, block);
}

TEST(Stm32CalibrationFlash, SingleBankOrBank2BootOptionBytesRefuseWritesAndStillRead) {
  for (const bool single_bank : {true, false}) {
    SCOPED_TRACE(single_bank ? "DBANK = 0" : "BFB2 = 1");
    FlashModel model;
    ASSERT_TRUE(commit(model, calibration_bytes(1)));
    if (single_bank) {
      model.set_dual_bank(false);
    } else {
      model.set_boot_from_bank2(true);
    }
    model.power_on();
    CalibrationStore store(model);
    EXPECT_FALSE(store.writable());
    const std::vector<std::uint8_t> block = calibration_bytes(2);
    EXPECT_FALSE(store.write(block.data(), block.size()));
    EXPECT_EQ(store.commit_error(), fw::CommitError::flash);
    EXPECT_EQ(store.flash_status(), fw::FlashStatus::refused);
    EXPECT_EQ(model.operations().size(), 31u);  // nothing after the first commit
    EXPECT_EQ(boot(model).bytes, calibration_bytes(1));
  }
}

TEST(Stm32CalibrationFlash, AWriteProtectedPageFailsWithWrperrAndKeepsTheOldBlock) {
  FlashModel model;
  ASSERT_TRUE(commit(model, calibration_bytes(1)));  // slot A
  model.write_protect_page(127);                     // slot B
  model.power_on();
  CalibrationStore store(model);
  const std::vector<std::uint8_t> block = calibration_bytes(2);
  EXPECT_FALSE(store.write(block.data(), block.size()));
  EXPECT_EQ(store.commit_error(), fw::CommitError::flash);
  EXPECT_EQ(store.flash_status(), fw::FlashStatus::failed);
  EXPECT_EQ(store.last_error_flags(), flash::Sr::WRPERR.mask());
  EXPECT_EQ(model.sr(), 0u);
  EXPECT_EQ(flash::Cr::LOCK.decode(model.cr()), 1u);
  EXPECT_EQ(boot(model).bytes, calibration_bytes(1));
}

TEST(Stm32CalibrationFlash, AFlashThatStaysBusyMakesWriteGiveUpAtThePollLimit) {
  FlashModel model;
  ASSERT_TRUE(commit(model, calibration_bytes(1)));
  model.power_on();
  model.hold_busy(true);
  CalibrationStore store(model, 1000);
  const std::vector<std::uint8_t> block = calibration_bytes(2);
  EXPECT_FALSE(store.write(block.data(), block.size()));
  EXPECT_TRUE(store.timed_out());
  EXPECT_EQ(model.operations().size(), 32u);              // the erase started and never ended
  EXPECT_FALSE(store.write(block.data(), block.size()));  // still running: no second commit
  model.hold_busy(false);
  std::vector<std::uint8_t> back(2048);
  back.resize(store.read(back.data(), back.size()));  // finishes the commit first
  EXPECT_FALSE(store.timed_out());
  EXPECT_EQ(back, block);
  EXPECT_TRUE(model.violations().empty());
}

TEST(Stm32CalibrationFlash, RefusesAnEmptyOrOversizedBlockWithoutTouchingFlash) {
  FlashModel model;
  CalibrationStore store(model);
  std::vector<std::uint8_t> big(CalibrationStore::Journal::kCapacity + 1, 0x11);
  EXPECT_FALSE(store.write(big.data(), big.size()));
  EXPECT_EQ(store.commit_error(), fw::CommitError::bad_size);
  EXPECT_FALSE(store.write(big.data(), 0));
  EXPECT_TRUE(model.operations().empty());
  big.pop_back();  // exactly the capacity (2016 bytes) fits
  EXPECT_TRUE(store.write(big.data(), big.size()));
  std::vector<std::uint8_t> back(2048);
  EXPECT_EQ(store.read(back.data(), back.size()), big.size());
  back.resize(big.size());
  EXPECT_EQ(back, big);
}

TEST(Stm32CalibrationFlash, DriverRefusesAddressesOutsideTheCalibrationPages) {
  FlashModel model;
  flash::FlashDriver<FlashModel> driver(model);
  std::uint8_t bytes[8];
  EXPECT_EQ(driver.erase_page(0x0800'0000), fw::FlashStatus::refused);  // bank 1: the image
  EXPECT_EQ(driver.erase_page(kSlotA - 8), fw::FlashStatus::refused);   // bank 2 page 125
  EXPECT_EQ(driver.program_double_word(kSlotA + 4, 0), fw::FlashStatus::refused);
  EXPECT_EQ(driver.program_double_word(0x0808'0000, 0), fw::FlashStatus::refused);
  EXPECT_EQ(driver.read(flash::kStorageEnd - 8, bytes, 16), fw::FlashStatus::refused);
  EXPECT_EQ(driver.read(kSlotA + 4, bytes, 8), fw::FlashStatus::refused);
  EXPECT_EQ(model.accesses(), 1u);  // OPTR at construction, nothing else
}

TEST(Stm32CalibrationFlash, EccErrorInAReadGoesThroughTheNmiHookAndReadsAsEccFault) {
  FlashModel model;
  flash::FlashDriver<FlashModel> driver(model);
  model.at(kSlotA + 8).ecc_bad = true;
  const std::uint32_t faults = flash::ecc_fault_log().faults;
  std::uint8_t bytes[16];
  EXPECT_EQ(driver.read(kSlotA, bytes, 16), fw::FlashStatus::ecc_fault);
  EXPECT_EQ(flash::ecc_fault_log().faults, faults + 2);  // both words of the double word
  EXPECT_EQ(flash::Eccr::ADDR_ECC.decode(flash::ecc_fault_log().last_eccr), 0x3'F008u);
  EXPECT_EQ(flash::Eccr::BK_ECC.decode(flash::ecc_fault_log().last_eccr), 1u);
  EXPECT_EQ(flash::Eccr::ECCD.decode(model.eccr()), 0u);  // cleared by the hook
  EXPECT_FALSE(flash::ecc_fault_log().expecting);
  EXPECT_EQ(model.fatal_nmis(), 0u);
  EXPECT_EQ(driver.read(kSlotA, bytes, 8), fw::FlashStatus::ok);  // the good double word
}

TEST(Stm32CalibrationFlash, NmiHookRefusesOtherNmisAndEccErrorsOutsideARead) {
  FlashModel model;
  flash::EccFaultLog log;
  EXPECT_FALSE(flash::handle_ecc_nmi(model, log));  // ECCD clear: e.g. the clock security NMI
  EXPECT_EQ(log.faults, 0u);
  model.at(kSlotA).ecc_bad = true;
  model.nmi = [] {};
  (void)model.read(kSlotA);  // sets ECCD as a read outside FlashDriver::read would
  EXPECT_FALSE(flash::handle_ecc_nmi(model, log));  // counted, cleared, but fatal
  EXPECT_EQ(log.faults, 1u);
  EXPECT_EQ(flash::Eccr::ECCD.decode(model.eccr()), 0u);
  log.expecting = true;
  (void)model.read(kSlotA);
  EXPECT_TRUE(flash::handle_ecc_nmi(model, log));
}

// Two commits (A: block 1, B: block 2), then slot B damaged by `damage`: the reason, and boot
// falls back to block 1.
struct Damage {
  const char* what;
  void (*apply)(FlashModel&);
  SlotStatus reason;
};

void set_word(FlashModel& m, std::uint32_t address, std::uint32_t value) {
  std::uint64_t& v = m.at(address & ~7u).value;
  const unsigned shift = (address & 4u) ? 32 : 0;
  v = (v & ~(std::uint64_t{0xFFFF'FFFF} << shift)) | (std::uint64_t{value} << shift);
}

const Damage kDamages[] = {
    {"a flipped bit in the block", [](FlashModel& m) { m.at(kSlotB + 40).value ^= 1; },
     SlotStatus::bad_crc},
    {"a torn header double word", [](FlashModel& m) { m.at(kSlotB).ecc_bad = true; },
     SlotStatus::ecc_fault},
    {"a torn block double word", [](FlashModel& m) { m.at(kSlotB + 64).ecc_bad = true; },
     SlotStatus::ecc_fault},
    {"a torn marker", [](FlashModel& m) { m.at(kSlotB + 0x7F8).ecc_bad = true; },
     SlotStatus::ecc_fault},
    {"no marker", [](FlashModel& m) { m.at(kSlotB + 0x7F8).value = FlashModel::kErased; },
     SlotStatus::uncommitted},
    {"a half-programmed marker",
     [](FlashModel& m) { m.at(kSlotB + 0x7F8).value |= 0x0000'00FF'0000'0000ull; },
     SlotStatus::uncommitted},
    {"something else where the marker goes",
     [](FlashModel& m) { m.at(kSlotB + 0x7F8).value = 0x1234; }, SlotStatus::bad_marker},
    {"a wrong magic", [](FlashModel& m) { set_word(m, kSlotB, 0x4C414350); },
     SlotStatus::bad_magic},
    {"journal layout 2", [](FlashModel& m) { set_word(m, kSlotB + 4, 2u | (208u << 16)); },
     SlotStatus::unknown_version},
    {"length 0", [](FlashModel& m) { set_word(m, kSlotB + 4, 1u); }, SlotStatus::bad_length},
    {"length beyond the page", [](FlashModel& m) { set_word(m, kSlotB + 4, 1u | (2017u << 16)); },
     SlotStatus::bad_length},
    {"the whole page erased",
     [](FlashModel& m) {
       for (std::uint32_t a = kSlotB; a < kSlotB + 0x800; a += 8) m.at(a) = {};
     },
     SlotStatus::erased},
};

TEST(Stm32CalibrationFlash, EachDamagedSlotIsRejectedWithItsReasonAndBootFallsBack) {
  for (const Damage& d : kDamages) {
    SCOPED_TRACE(d.what);
    FlashModel model;
    ASSERT_TRUE(commit(model, calibration_bytes(1)));
    ASSERT_TRUE(commit(model, calibration_bytes(2)));
    d.apply(model);
    const Boot b = boot(model);
    EXPECT_EQ(b.scan.slots[1].status, d.reason) << fw::slot_status_name(b.scan.slots[1].status);
    EXPECT_EQ(b.scan.slots[0].status, SlotStatus::valid);
    EXPECT_EQ(b.bytes, calibration_bytes(1));
    EXPECT_EQ(model.fatal_nmis(), 0u);
    // the next commit replaces the damaged slot, not the good one
    ASSERT_TRUE(commit(model, calibration_bytes(3)));
    const Boot after = boot(model);
    EXPECT_EQ(after.bytes, calibration_bytes(3));
    EXPECT_EQ(after.scan.newest, 1);
    EXPECT_EQ(after.scan.slots[0].sequence, 1u);
    EXPECT_TRUE(model.violations().empty());
  }
}

// A layout v1 block (calibration.hpp), built field by field as older firmware wrote it.
std::vector<std::uint8_t> v1_block() {
  std::vector<std::uint8_t> b(fw::kCalibrationBlockSizeV1, 0);
  auto put = [&b](std::size_t at, const void* v, std::size_t n) { std::memcpy(&b[at], v, n); };
  const std::uint32_t magic = fw::kCalibrationMagic;
  const std::uint16_t version = 1, size = fw::kCalibrationBlockSizeV1;
  put(0, &magic, 4);
  put(4, &version, 2);
  put(6, &size, 2);
  b[8] = 1;  // kf_count
  b[9] = 1;  // stroke origin valid
  const float kf = 2.75f, gain = 1.0f, offset_pa = 12.5f, spring_N_per_mm = 0.0439f;
  const std::int32_t origin = 321;
  put(76, &kf, 4);
  put(144, &gain, 4);
  put(148, &offset_pa, 4);
  put(172, &spring_N_per_mm, 4);
  put(176, &origin, 4);
  const std::uint32_t crc = proto::crc32(b.data(), 180);
  put(180, &crc, 4);
  return b;
}

TEST(Stm32CalibrationFlash, V1BlockFromOlderFirmwareIsMigratedThenStoredAsV2) {
  FlashModel model;
  ASSERT_TRUE(commit(model, v1_block()));  // what older firmware left in the journal
  const fw::CalibrationLoad old = fw::load_calibration(boot(model).bytes);
  ASSERT_EQ(old.status, fw::CalibrationStatus::ok);
  EXPECT_EQ(old.layout_version, 1);
  EXPECT_EQ(old.data.kf_N_per_A[0], 2.75f);
  EXPECT_EQ(old.data.pressure_offset_Pa[0], 12.5f);
  EXPECT_EQ(old.data.pressure_gain[0], 1.0f);
  EXPECT_FLOAT_EQ(old.data.spring_k_N_per_m, 43.9f);
  EXPECT_EQ(old.data.stroke_origin_counts, 321);
  const fw::CalibrationBlock v2 = fw::serialize_calibration(old.data);
  ASSERT_TRUE(commit(model, {v2.begin(), v2.end()}));
  const Boot b = boot(model);
  const fw::CalibrationLoad now = fw::load_calibration(b.bytes);
  ASSERT_EQ(now.status, fw::CalibrationStatus::ok);
  EXPECT_EQ(now.layout_version, 2);
  EXPECT_EQ(now.data, old.data);
  EXPECT_EQ(b.scan.slots[0].length, fw::kCalibrationBlockSizeV1);  // v1 kept as the older slot
  EXPECT_EQ(b.scan.slots[1].length, fw::kCalibrationBlockSizeV2);
}

}  // namespace
}  // namespace palp::stm32::test
