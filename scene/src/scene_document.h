// A scene read from a JSON document already parsed: what parseScene does after the parse. The
// built-in scenes hand their generated documents here directly, without a text in between.
#pragma once

#include <collide/scene/scene.h>

#include <nlohmann/json.hpp>

#include <filesystem>
#include <string_view>

namespace collide::scene {

// Throws collide::Error as parseScene does for what the document holds. Integers must be as the
// parser gives them: non-negative ones unsigned (normalizeIntegers). Each body's JSON is emptied
// (null) once the body is read, so that the document and the bodies built from it are not held
// whole together.
Scene readSceneDocument(nlohmann::json& document, std::string_view source,
                        const std::filesystem::path& baseDir = ".", const LoadOptions& options = {});

// Makes every non-negative integer of `document` unsigned, as the parser reads "5" (a document
// built in code holds 5 as a signed integer), so that fields read as unsigned accept it.
void normalizeIntegers(nlohmann::json& document);

}  // namespace collide::scene
