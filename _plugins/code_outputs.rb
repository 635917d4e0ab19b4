# frozen_string_literal: true

# Shows under each ```python block what it printed when the page runner last ran the page,
# from _data/outputs/<page path under _pages/, "/" as "__">.json (written by
# `python -m course.snippets --write-outputs`; tests/course/test_pages.py fails while a
# stored output differs from what the block prints now, so what the page shows is current).
#
# The file lists every ```python fence of the page in page order, as the runner's parser
# finds them, each with its first code line and its output (null: a block that is not run).
# The Nth python block of the rendered page takes the Nth entry, and only if its first code
# line is the entry's: a page whose blocks and outputs file disagree gets no outputs and a
# build warning (which fails tests/site/test_site.py) rather than outputs under the wrong
# blocks.
#
# An output of up to LONG lines is shown open; a longer one is folded, its summary saying
# how many lines it has. Styles: the "Block outputs" section of assets/css/main.css.
#
# Each printed line that is not empty sits in a <span class="code-output-line"> of its own,
# and the newlines stay between the spans as text: the stylesheet wraps a line too long
# for the box with a hanging indent (a `sw2sim check` line keeps its "Fix: ..." in view
# instead of behind a scroll bar), which needs one box a line, while the text of the
# <samp> (what a copy or a screen reader gets) is still exactly what the block printed.
require "cgi/escape"

module Sw2simSite
  module CodeOutputs
    FOLDER = "outputs" # under _data/
    LONG = 15
    # A rendered python block, from kramdown's wrapper to the end of rouge's <pre>; whatever
    # _plugins/code_blocks.rb adds (header, badges) may or may not be in it yet.
    PYTHON_BLOCK = %r{<div\b[^>]*\bclass="[^"]*\blanguage-python\b[^"]*\bhighlighter-rouge\b[^"]*"[^>]*>
                      .*?<code>(.*?)</code>\s*</pre>\s*</div>\s*</div>}xm.freeze
    TAG = /<[^>]+>/.freeze

    module_function

    # The page's entry in _data/outputs, or nil: its path under _pages/ with "/" as "__".
    def entries(page)
      path = page.relative_path.to_s
      return nil unless path.start_with?("_pages/") && path.end_with?(".md")

      name = path.delete_prefix("_pages/").delete_suffix(".md").gsub("/", "__")
      data = page.site.data.dig(FOLDER, name)
      data.is_a?(Hash) ? data["blocks"] : nil
    end

    def decorate(html, blocks, where)
      count = 0
      mismatch = nil
      decorated = html.gsub(PYTHON_BLOCK) do
        block = Regexp.last_match(0)
        entry = blocks[count]
        shown = first_line(CGI.unescapeHTML(Regexp.last_match(1).gsub(TAG, "")))
        mismatch ||= "python block #{count + 1} begins `#{shown}`, its output is for " \
                     "`#{entry && entry["code"]}`" if entry.nil? || entry["code"] != shown
        count += 1
        output = entry && entry["output"]
        output.is_a?(String) && !output.empty? ? block + details(output) : block
      end
      mismatch ||= "#{count} python blocks, outputs for #{blocks.length}" if count != blocks.length
      return decorated unless mismatch

      Jekyll.logger.warn "Code outputs:", "#{where}: outputs not shown, _data/#{FOLDER} is out of " \
                                          "date (#{mismatch}); run `python -m course.snippets --write-outputs`"
      html
    end

    def first_line(code)
      code.each_line.map(&:strip).find { |line| !line.empty? } || ""
    end

    def details(output)
      text = output.rstrip
      lines = text.count("\n") + 1
      long = lines > LONG
      summary = long ? "Show output (#{lines} lines)" : "Output"
      %(<details class="code-output"#{long ? "" : " open"}><summary>#{summary}</summary>) +
        %(<div class="code-output-text" tabindex="0"><samp>#{lines_html(text)}</samp></div></details>)
    end

    # The output's lines, escaped, each non-empty one in its own span with its indentation
    # (_plugins/code_blocks.rb). An empty line is left bare: an empty inline box would take
    # no height and the blank line would vanish.
    def lines_html(text)
      text.split("\n", -1).map do |line|
        line.empty? ? "" : CodeBlocks.line_html(CGI.escapeHTML(line))
      end.join("\n")
    end
  end
end

Jekyll::Hooks.register [:pages, :documents], :post_convert do |page|
  next unless page.output_ext == ".html"

  blocks = Sw2simSite::CodeOutputs.entries(page)
  next unless blocks

  page.content = Sw2simSite::CodeOutputs.decorate(page.content, blocks, page.relative_path)
end
