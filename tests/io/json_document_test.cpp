// Whole JSON documents from users' files: every refusal names the file and the line, and what
// nlohmann would accept silently (a key given twice) is refused.

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "physics/material.hpp"
#include "support/scratch_folder.hpp"
#include "tools/tool_json.hpp"
#include "util/json_document.hpp"
#include "util/json_fields.hpp"

namespace sandtin {
namespace {

namespace fs = std::filesystem;

std::string error_of(const std::string& text) {
    try {
        parse_json_document(text, "doc.json");
    } catch (const JsonInputError& e) {
        return e.what();
    }
    ADD_FAILURE() << "parsed: " << text;
    return {};
}

bool contains(const std::string& s, const std::string& part) {
    return s.find(part) != std::string::npos;
}

TEST(JsonDocument, ParsesAValidDocumentAsNlohmannDoes) {
    const std::string text = "{\n \"a\": [1, 2.5, \"x\", null],\n \"b\": {\"a\": true}\n}\n";
    EXPECT_EQ(parse_json_document(text, "doc.json"), nlohmann::json::parse(text));
    // The same key in different objects, or in an array's objects, is not a repetition.
    EXPECT_NO_THROW(parse_json_document(R"([{"k": 1}, {"k": 2}, {"k": {"k": 3}}])", "d"));
}

TEST(JsonDocument, ASyntaxErrorNamesItsLine) {
    EXPECT_TRUE(contains(error_of("{\n\"a\": 1,\n\"b\": }"), "doc.json:3: not valid JSON"))
        << error_of("{\n\"a\": 1,\n\"b\": }");
}

// nlohmann throws out_of_range without an offset for a number beyond double's range.
TEST(JsonDocument, ANumberBeyondDoubleRangeNamesItsLine) {
    // Followed by a comma, by a newline (the lexer's one-character lookahead), and at the end.
    for (const char* text :
         {"{\n\"a\": 1,\n\"b\": 1e400, \"c\": 0}", "{\n\"a\": 1,\n\"b\": -1e400\n}", "\n\n1e400"}) {
        const std::string e = error_of(text);
        EXPECT_TRUE(contains(e, "doc.json:3: not valid JSON")) << e;
        EXPECT_TRUE(contains(e, "1e400")) << e;
    }
}

TEST(JsonDocument, AKeyGivenTwiceInOneObjectIsRefusedWithItsLine) {
    const std::string e =
        error_of("{\n \"radius\": 0.1,\n \"inner\": {\"a\": 1},\n \"radius\": 2\n}");
    EXPECT_TRUE(contains(e, "doc.json:4: the key 'radius' is given twice")) << e;
    // In a nested object too.
    EXPECT_TRUE(contains(error_of("[{\"a\": {\"b\": 1,\n\"b\": 1}}]"), "doc.json:2: the key 'b'"));
}

class JsonFiles : public test::ScratchFolderTest {
  protected:
    JsonFiles() : ScratchFolderTest("json") {}
    fs::path write(const std::string& name, const std::string& text) {
        const fs::path p = dir_ / name;
        std::ofstream(p) << text;
        return p;
    }
};

// Tool and material files go through the same reader: the error names the file and the line.
TEST_F(JsonFiles, ToolAndMaterialFilesNameTheFileAndLineOfWhatIsWrong) {
    const fs::path tool = write("t.json", "{\"contour\": \"circle\",\n\"radius\": 1e400}");
    try {
        load_tool_asset(tool.string());
        ADD_FAILURE() << "a tool with radius 1e400 loaded";
    } catch (const JsonInputError& e) {
        EXPECT_TRUE(contains(e.what(), tool.string() + ":2: not valid JSON")) << e.what();
    }
    const fs::path twice =
        write("twice.json", "{\"contour\": \"circle\",\n\"contour\": \"rectangle\"}");
    try {
        load_tool_asset(twice.string());
        ADD_FAILURE() << "a tool giving its contour twice loaded";
    } catch (const JsonInputError& e) {
        EXPECT_TRUE(contains(e.what(), twice.string() + ":2: the key 'contour'")) << e.what();
    }
    const fs::path materials = write("m.json", "[{\"name\": \"a\",\n \"name\": \"b\"}]");
    try {
        MaterialTable::load(materials);
        ADD_FAILURE() << "a material giving its name twice loaded";
    } catch (const JsonInputError& e) {
        EXPECT_TRUE(contains(e.what(), materials.string() + ":2: the key 'name'")) << e.what();
    }
    try {
        MaterialTable::load(dir_ / "missing.json");
        ADD_FAILURE() << "a missing material file loaded";
    } catch (const JsonInputError& e) {
        EXPECT_TRUE(contains(e.what(), "material file: cannot")) << e.what();
        EXPECT_TRUE(contains(e.what(), "missing.json")) << e.what();
    }
}

}  // namespace
}  // namespace sandtin
