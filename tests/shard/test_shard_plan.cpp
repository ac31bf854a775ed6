// The shard plan: --shard K/N parsed and checked, trials numbered in the order
// the script asks about them, which shard may save which, and shard-plan.csv
// written and read back (with its errors).
#include <catch2/catch.hpp>

#include "rollsense/shard.hpp"
#include "temp_dir.hpp"

using namespace rollsense;
namespace rt = rollsense::testing;

TEST_CASE("the shard K/N: whole numbers with 0 <= K < N and N >= 2", "[shard]") {
    auto s = parse_shard("2/4", "--shard");
    REQUIRE(s.ok());
    CHECK(s->index == 2);
    CHECK(s->count == 4);
    CHECK(s->text() == "2/4");
    CHECK(parse_shard("0/2", "--shard").ok());
    for (const char* bad : {"0/1", "1/1", "4/4", "5/4", "1/0", "0/0", "-1/4", "1", "1/", "/4", "a/b", "1.5/4", "1/4/2", ""}) {
        INFO(bad);
        auto r = parse_shard(bad, "--shard");
        REQUIRE_FALSE(r.ok());
        CHECK(r.error().message.find("--shard") != std::string::npos);
    }
    CHECK(parse_shard("4/4", "--shard").error().message.find("0/4 ... 3/4") != std::string::npos);
    CHECK(parse_shard("abc", "--shard").error().message.find("expects K/N") != std::string::npos);
    CHECK(parse_shard("0/1", "--shard").error().message ==
          "--shard 0/1: --shard K/N needs N >= 2; run without --shard for one process");
}

TEST_CASE("a shard claims every Nth trial it is asked about, in order, once", "[shard]") {
    ShardPlan plan(Shard{1, 3});
    CHECK_FALSE(plan.claim("t0"));
    CHECK(plan.claim("t1"));
    CHECK_FALSE(plan.claim("t2"));
    CHECK_FALSE(plan.claim("t3"));
    CHECK(plan.claim("t4"));
    // Asking again (a script that checks twice) keeps the trial's index.
    CHECK(plan.claim("t1"));
    CHECK_FALSE(plan.claim("t0"));
    CHECK(plan.trials() == std::vector<std::string>{"t0", "t1", "t2", "t3", "t4"});

    CHECK(plan.check_save("t1").ok());
    CHECK(plan.check_save("t4").ok());
    auto foreign = plan.check_save("t2");
    REQUIRE_FALSE(foreign.ok());
    CHECK(foreign.message().find("belongs to shard 2/3, not to this shard 1/3") != std::string::npos);
    auto unasked = plan.check_save("t9");
    REQUIRE_FALSE(unasked.ok());
    CHECK(unasked.message().find("did not ask rs.has_trial('t9')") != std::string::npos);
}

TEST_CASE("shard-plan.csv lists the trials in order with their shard and reads back", "[shard]") {
    rt::TempDir dir;
    ShardPlan plan(Shard{0, 2});
    for (const char* id : {"C1-v10-r001", "C1-v10-r002", "C1-v10-r003"}) (void)plan.claim(id);
    CHECK(plan.csv() == "trial_id,shard\nC1-v10-r001,0\nC1-v10-r002,1\nC1-v10-r003,0\n");
    rt::write_file(dir / kShardPlanFile, plan.csv());
    auto read = read_shard_plan(dir.path(), 2);
    REQUIRE(read.ok());
    CHECK(*read == plan.trials());

    SECTION("read as a split another N ways, the shard column disagrees") {
        auto r = read_shard_plan(dir.path(), 3);
        REQUIRE_FALSE(r.ok());
        CHECK(r.error().message.find("shard-plan.csv:4: column 'shard'") != std::string::npos);
        CHECK(r.error().message.find("belongs to shard 2") != std::string::npos);
    }
    SECTION("a trial planned twice") {
        rt::write_file(dir / kShardPlanFile, "trial_id,shard\na,0\nb,1\na,0\n");
        auto r = read_shard_plan(dir.path(), 2);
        REQUIRE_FALSE(r.ok());
        CHECK(r.error().message.find("shard-plan.csv:4") != std::string::npos);
        CHECK(r.error().message.find("planned twice (first on line 2)") != std::string::npos);
    }
    SECTION("no plan at all") {
        std::filesystem::remove(dir / kShardPlanFile);
        CHECK_FALSE(read_shard_plan(dir.path(), 2).ok());
    }
}
