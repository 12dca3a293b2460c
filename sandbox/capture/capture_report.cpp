#include "capture/capture_report.h"

#include "atomic_file.h"
#include "output_transaction.h"
#include "csv_writer.h"
#include "render/png_codec.h"

#include <cstdio>
#include <filesystem>

namespace substep::capture {

namespace fs = std::filesystem;

namespace {

std::string escapeHtml(std::string_view text) {
    std::string out;
    for (const char c : text) {
        switch (c) {
            case '&':
                out += "&amp;";
                break;
            case '<':
                out += "&lt;";
                break;
            case '>':
                out += "&gt;";
                break;
            case '"':
                out += "&quot;";
                break;
            default:
                out += c;
        }
    }
    return out;
}

std::string number(double value) {
    std::string text;
    appendNumber(text, value);
    return text;
}

/// The report's files go into one transaction: the page and its images appear together.
void writeFile(OutputTransaction& outputs, const fs::path& path, const std::string& bytes) {
    outputs.add("--report", path.string()).write(bytes);
}

std::string frameStem(const std::string& capture, long long frame) {
    char stem[32];
    std::snprintf(stem, sizeof stem, "frame_%05lld", frame);
    return capture + "/" + stem;
}

void appendImages(OutputTransaction& outputs, std::string& html, const fs::path& directory, const std::string& capture,
                  const FrameMismatch& mismatch) {
    const std::string stem = frameStem(capture, mismatch.frame);
    fs::create_directories(directory / capture);
    writeFile(outputs, directory / (stem + "_golden.png"), render::encodePng(mismatch.golden));
    writeFile(outputs, directory / (stem + "_new.png"), render::encodePng(mismatch.fresh));
    writeFile(outputs, directory / (stem + "_diff.png"),
              render::encodePng(
                  differenceHeatMap(mismatch.golden, mismatch.fresh, mismatch.pixelTolerance)));
    html += "<table class=images><tr><th>golden</th><th>new</th><th>difference (over " +
            std::to_string(mismatch.pixelTolerance) + ": red to yellow)</th></tr><tr>";
    for (const char* kind : {"golden", "new", "diff"}) {
        html +=
            "<td><img src=\"" + escapeHtml(stem) + "_" + kind + ".png\" alt=\"" + kind + "\"></td>";
    }
    html += "</tr></table>\n";
}

void appendStateTable(std::string& html, const StateComparison& state) {
    if (!state.structure.empty()) {
        html += "<p>State: " + escapeHtml(state.structure) + "</p>\n";
        return;
    }
    html += "<p>State: " + std::to_string(state.outOfTolerance) + " of " +
            std::to_string(state.compared) + " values out of tolerance";
    if (state.differences.size() < state.outOfTolerance) {
        html += " (the first " + std::to_string(state.differences.size()) + " listed)";
    }
    html +=
        "</p>\n<table "
        "class=state><tr><th>value</th><th>golden</th><th>new</th><th>difference</th><th>allowed</"
        "th></tr>\n";
    for (const StateDifference& difference : state.differences) {
        html += "<tr><td>" + escapeHtml(difference.what) + "</td><td>" + number(difference.golden) +
                "</td><td>" + number(difference.fresh) + "</td><td>" +
                number(difference.fresh - difference.golden) + "</td><td>" +
                number(difference.allowed) + "</td></tr>\n";
    }
    html += "</table>\n";
}

}  // namespace

void prepareReportFolder(const std::string& directory) {
    std::error_code error;
    fs::create_directories(directory, error);
    if (!fs::is_directory(directory, error)) {
        throw OutputError("--report " + directory + ": cannot create the folder" +
                          (fs::exists(directory, error) ? " (a file has that name)" : ""));
    }
}

void writeCaptureReport(const std::string& directory, const std::string& scriptFile,
                        const std::vector<CaptureResult>& results) {
    const fs::path folder(directory);
    prepareReportFolder(directory);
    OutputTransaction outputs;

    std::size_t checked = 0;
    std::size_t differing = 0;
    for (const CaptureResult& result : results) {
        checked += result.checked ? 1 : 0;
        differing += result.checked && !result.matches() ? 1 : 0;
    }
    std::string html =
        "<!DOCTYPE html>\n<html><head><meta charset=\"utf-8\"><title>substep capture: " +
        escapeHtml(scriptFile) +
        "</title>\n<style>body{font-family:sans-serif;margin:1em "
        "2em}table{border-collapse:collapse}"
        "td,th{border:1px solid #ccc;padding:2px 6px;text-align:left}table.state "
        "td{font-family:monospace}"
        "table.images td{vertical-align:top}img{image-rendering:pixelated;min-width:320px}"
        ".ok{color:#080}.bad{color:#b00}</style></head><body>\n";
    html += "<h1>substep capture " + escapeHtml(scriptFile) + "</h1>\n<p>" +
            std::to_string(checked) + " capture" + (checked == 1 ? "" : "s") + " checked, " +
            std::to_string(differing) + " differ" + (differing == 1 ? "s" : "") + ".</p>\n<ul>\n";
    for (const CaptureResult& result : results) {
        if (!result.checked) continue;
        html += "<li><a href=\"#" + escapeHtml(result.name) + "\">" + escapeHtml(result.name) +
                "</a> (" + escapeHtml(result.scene) + "): " +
                (result.matches() ? "<span class=ok>matches</span>"
                                  : "<span class=bad>differs</span>") +
                "</li>\n";
    }
    html += "</ul>\n";
    for (const CaptureResult& result : results) {
        if (!result.checked || result.matches()) continue;
        html += "<h2 id=\"" + escapeHtml(result.name) + "\">" + escapeHtml(result.name) +
                "</h2>\n<ul>\n";
        for (const std::string& line : result.lines)
            html += "<li class=bad>" + escapeHtml(line) + "</li>\n";
        html += "</ul>\n";
        for (const FrameMismatch& mismatch : result.frames) {
            html += "<h3>" + escapeHtml(result.name) + ", frame " + std::to_string(mismatch.frame) +
                    "</h3>\n";
            if (mismatch.image) appendImages(outputs, html, folder, result.name, mismatch);
            if (mismatch.state) appendStateTable(html, *mismatch.state);
        }
    }
    html += "</body></html>\n";
    writeFile(outputs, folder / "index.html", html);
    outputs.commit();
}

}  // namespace substep::capture
