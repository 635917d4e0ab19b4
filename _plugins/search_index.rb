# frozen_string_literal: true

# Writes assets/search-data.json, the documents of the site search (assets/js/search.js
# builds a lunr index from them in the browser, on the reader's first use of the box).
#
# One document per section of every page of the site: the text before the first heading,
# then one per h2 and per h3 heading, so that a result links to the heading's anchor.
# A document holds plain text only:
#
#   {"url": "/practice-5/ackermann-geometry/#equation-4", "page": "Ackermann geometry",
#    "section": "Equation 4", "text": "Let l be the wheelbase, ...",
#    "code": "knuckle_angles load_package sw2sim"}
#
# Prose keeps its inline code and the letters of its formulas; code blocks are left out
# of the text (their tokens would swamp it) but their identifiers, the names a reader
# may look up (`load_package`, `MjData`, `example_5`), go into `code`.
require "cgi/escape"
require "json"

module Sw2simSite
  module SearchIndex
    OUTPUT = "assets/search-data.json"

    # The heading of a section and everything up to the next h2 or h3.
    HEADING = %r{<h([23])\b[^>]*?\bid="([^"]+)"[^>]*>(.*?)</h\1>}m.freeze
    CODE_BLOCK = %r{<pre\b[^>]*>(.*?)</pre>}m.freeze
    # Code block headers (_plugins/code_blocks.rb) say "python" or name a file, and a block's
    # output (_plugins/code_outputs.rb) is what the code printed: neither is prose.
    CODE_HEADER = %r{<div class="code-(?:header|skip)">.*?</div>|<details class="code-output".*?</details>}m.freeze
    DISPLAY_MATH = /\\\[.*?\\\]/m.freeze
    INLINE_MATH = /\\\((.*?)\\\)/m.freeze
    TAG = /<[^>]+>/.freeze
    # Block tags part words; inline ones (<code>, <em>, <a>) sit inside a sentence.
    BLOCK_TAG = %r{</?(?:p|div|li|ul|ol|dl|dt|dd|h\d|table|tr|td|th|br|hr|figure|figcaption|
                     blockquote|details|summary)\b[^>]*>}xi.freeze
    # Names with an underscore, a digit or an inner capital: `load_package`, `sw2sim`,
    # `MjData`. Plain words in code are in the prose around it already.
    IDENTIFIER = /\b[A-Za-z_][A-Za-z0-9_]*\b/.freeze
    NAME_LIKE = /_|\d|[a-z][A-Z]/.freeze

    module_function

    # The pages of the sitemap (jekyll-sitemap's choice): the site's pages, less 404.
    def documents(site)
      pages = site.pages.select do |page|
        page.html? && page.data["sitemap"] != false && page.url != "/404.html"
      end
      pages.sort_by(&:url).flat_map { |page| sections(page, site.baseurl.to_s.chomp("/")) }
    end

    def sections(page, base)
      title = plain(page.data["title"].to_s)
      title = page.url if title.empty?
      parts = page.content.to_s.split(HEADING)
      # split with groups: intro, then (level, id, heading, body) for each heading.
      docs = [document("#{base}#{page.url}", title, "", parts.shift)]
      h2 = ""
      parts.each_slice(4) do |level, id, heading, body|
        heading = plain(heading)
        h2 = heading if level == "2"
        section = level == "3" && !h2.empty? ? "#{h2} › #{heading}" : heading
        docs << document("#{base}#{page.url}##{id}", title, section, body)
      end
      # A heading with nothing under it but subsections (the glossary's letters) has its
      # words in each subsection's heading already.
      docs.reject { |doc| doc["text"].empty? && doc["code"].empty? }
    end

    def document(url, title, section, html)
      html = html.to_s.gsub(CODE_HEADER, "")
      code = html.scan(CODE_BLOCK).flatten.map { |block| CGI.unescapeHTML(block.gsub(TAG, "")) }
      names = code.flat_map { |text| text.scan(IDENTIFIER) }.grep(NAME_LIKE).uniq
      prose = html.gsub(CODE_BLOCK, " ").gsub(DISPLAY_MATH, " ")
                  .gsub(INLINE_MATH) { math_letters(Regexp.last_match(1)) }
      { "url" => url, "page" => title, "section" => section, "text" => plain(prose),
        "code" => names.join(" ") }
    end

    # `\(\Phi_i\)` reads as "Phi_i" in the text and its excerpts.
    def math_letters(tex)
      tex.gsub(/\\([A-Za-z]+)/, '\1').delete("{}\\")
    end

    def plain(html)
      CGI.unescapeHTML(html.gsub(BLOCK_TAG, " ").gsub(TAG, "")).gsub(/\s+/, " ").strip
    end
  end

  # The JSON is a page of the site, so Jekyll writes it, keeps it on rebuilds and serves
  # it with `jekyll serve`; its text is filled in once every other page is rendered.
  class SearchIndexGenerator < Jekyll::Generator
    safe true
    priority :lowest

    def generate(site)
      page = Jekyll::PageWithoutAFile.new(site, site.source, File.dirname(SearchIndex::OUTPUT),
                                          File.basename(SearchIndex::OUTPUT))
      # Not a document page: no layout, not in the sitemap.
      page.data.merge!("layout" => nil, "sitemap" => false, "search_index" => true)
      page.content = ""
      site.pages << page
    end
  end
end

Jekyll::Hooks.register :site, :post_render do |site|
  page = site.pages.find { |p| p.data["search_index"] }
  next unless page

  page.output = JSON.generate(Sw2simSite::SearchIndex.documents(site))
end
