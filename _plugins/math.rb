# frozen_string_literal: true

# Math is typeset when the site is built: the pages carry KaTeX's HTML (and its MathML,
# for screen readers), and the browser loads only the KaTeX stylesheet and fonts.
#
# 1. kramdown writes each formula as a marker (this file's engine, registered under the
#    name `mathjax` that _config.yml gives: Jekyll wants a gem for any other name),
#    `<kramdown-math>\(...\)</kramdown-math>` inline or `<kramdown-math>\[...\]</kramdown-math>`
#    for one alone in its paragraph, the TeX HTML-escaped. Code blocks never hold one.
#    The layout links the KaTeX stylesheet on a page whose content holds a marker.
# 2. Once every page is rendered, all the formulas of the site go to tools/render-math.mjs
#    (KaTeX from node_modules, run by Node) in one JSON request on stdin; each marker is
#    replaced with the HTML that comes back. Display formulas sit in a
#    <span class="katex-display">, which scrolls sideways when wider than the page.
#
# A formula KaTeX cannot typeset stops the build with the page and the formula.
require "cgi/escape"
require "json"
require "open3"

module Sw2simSite
  module MathAtBuild
    MARKER = %r{<kramdown-math>\\([(\[])(.*?)\\[)\]]</kramdown-math>}m.freeze
    SCRIPT = "tools/render-math.mjs"

    # The kramdown math engine: a marker the :site hook below replaces.
    module Engine
      def self.call(converter, el, _opts)
        tex = converter.escape_html(el.value)
        block = el.options[:category] == :block
        marker = block ? "<kramdown-math>\\[#{tex}\\]</kramdown-math>\n" : "<kramdown-math>\\(#{tex}\\)</kramdown-math>"
        return marker if el.attr.empty?

        if block
          converter.format_as_block_html("div", el.attr, marker, 0)
        else
          converter.format_as_span_html("span", el.attr, marker)
        end
      end
    end

    module_function

    def pages(site)
      (site.pages + site.documents).select { |page| page.output.to_s.include?("<kramdown-math>") }
    end

    # Every distinct formula of the site, typeset in one run of Node.
    def typeset_site(site)
      pages = pages(site)
      return if pages.empty?

      started = Process.clock_gettime(Process::CLOCK_MONOTONIC)
      formulas = {}
      pages.each do |page|
        page.output.scan(MARKER) do |delimiter, tex|
          (formulas[[CGI.unescapeHTML(tex), delimiter == "["]] ||= []) << page.relative_path
        end
      end
      keys = formulas.keys
      results = run_katex(site, keys.map { |tex, display| { "tex" => tex, "display" => display } })
      failed = keys.zip(results).select { |_, result| result["error"] }
      unless failed.empty?
        report = failed.map do |(tex, display), result|
          "#{formulas[[tex, display]].uniq.join(', ')}: #{display ? 'displayed' : 'inline'} formula $$#{tex}$$: #{result['error']}"
        end
        raise Jekyll::Errors::FatalException, "KaTeX cannot typeset:\n  #{report.join("\n  ")}"
      end
      html = keys.zip(results).to_h { |key, result| [key, result["html"]] }
      pages.each do |page|
        page.output = page.output.gsub(MARKER) do
          html.fetch([CGI.unescapeHTML(Regexp.last_match(2)), Regexp.last_match(1) == "["])
        end
      end
      seconds = Process.clock_gettime(Process::CLOCK_MONOTONIC) - started
      Jekyll.logger.debug "Math:", format("%d formulas of %d pages typeset in %.2f s", keys.length, pages.length, seconds)
    end

    def run_katex(site, items)
      script = File.join(site.source, SCRIPT)
      raise Jekyll::Errors::FatalException, "math: #{script} not found" unless File.file?(script)

      begin
        out, err, status = Open3.capture3("node", script, stdin_data: JSON.generate(items))
      rescue Errno::ENOENT
        raise Jekyll::Errors::FatalException,
              "math: `node` not found; it typesets the formulas with KaTeX (run `make setup`)"
      end
      unless status.success?
        raise Jekyll::Errors::FatalException, "math: #{SCRIPT} failed (exit #{status.exitstatus}):\n#{err}"
      end

      results = JSON.parse(out)
      unless results.is_a?(Array) && results.length == items.length
        raise Jekyll::Errors::FatalException, "math: #{SCRIPT} answered #{results.length} results for #{items.length} formulas"
      end

      results
    end
  end
end

# Replaces kramdown's own MathJax engine, which writes bare \(...\) and \[...\].
Kramdown::Converter.add_math_engine(:mathjax, Sw2simSite::MathAtBuild::Engine)

Jekyll::Hooks.register :site, :post_render do |site|
  Sw2simSite::MathAtBuild.typeset_site(site)
end
